# `cmake --install build [--prefix DIR]`: the runtime library (the module targets listed in
# DRVSLAM_RUNTIME_MODULES, static, with every project target they link), their headers, the
# default vocabulary and drvslamConfig.cmake, so that a program finds it with
# find_package(drvslam) and links drvslam::drvslam. Included by the top-level CMakeLists.txt
# after src/drvslam, which defines DRVSLAM_RUNTIME_MODULES.
include(CMakePackageConfigHelpers)

if(NOT DRVSLAM_RUNTIME_MODULES)
  message(FATAL_ERROR "drvslam: DRVSLAM_RUNTIME_MODULES is empty; src/drvslam/CMakeLists.txt "
                      "must list the runtime module targets")
endif()

# The project's own targets among `targets` and everything they link, publicly or privately
# (a static library hands its private dependencies on to the final link, so the export needs
# them too). Imported targets (OpenCV, Ceres, ...) are left to find_dependency.
function(drvslam_link_closure out)
  set(pending ${ARGN})
  set(seen)
  while(pending)
    list(POP_FRONT pending target)
    if(NOT TARGET ${target})
      continue()
    endif()
    get_target_property(aliased ${target} ALIASED_TARGET)
    if(aliased)
      set(target ${aliased})
    endif()
    get_target_property(imported ${target} IMPORTED)
    if(imported OR target IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${target})
    get_target_property(links ${target} INTERFACE_LINK_LIBRARIES)
    get_target_property(type ${target} TYPE)
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(direct ${target} LINK_LIBRARIES)
      list(APPEND links ${direct})
    endif()
    foreach(link IN LISTS links)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
      if(TARGET ${link})
        list(APPEND pending ${link})
      endif()
    endforeach()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

drvslam_link_closure(drvslam_install_targets drvslam ${DRVSLAM_RUNTIME_MODULES})
install(TARGETS ${drvslam_install_targets} EXPORT drvslamTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT drvslamTargets NAMESPACE drvslam::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drvslam)

# Headers: each installed module's folder (not its subfolders: src/drvslam holds the facade, its
# subfolders are modules of their own), under include/ as the sources include them.
set(drvslam_header_dirs)
foreach(target IN LISTS drvslam_install_targets)
  get_target_property(dir ${target} SOURCE_DIR)
  list(APPEND drvslam_header_dirs ${dir})
endforeach()
list(REMOVE_DUPLICATES drvslam_header_dirs)
foreach(dir IN LISTS drvslam_header_dirs)
  file(GLOB headers CONFIGURE_DEPENDS ${dir}/*.h)
  file(RELATIVE_PATH destination ${PROJECT_SOURCE_DIR}/src ${dir})
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${destination})
endforeach()

# The default vocabulary, which relocalization and loop closing load when the settings name
# none: installed to share/drvslam, where DefaultVocabularyPath() looks (the configured prefix is
# compiled in) and which drvslamConfig.cmake names as drvslam_DEFAULT_VOCABULARY, also for a
# tree installed elsewhere with --prefix.
get_directory_property(vocabulary_file DIRECTORY ${PROJECT_SOURCE_DIR}/src/drvslam/loop
                       DEFINITION DRVSLAM_DEFAULT_VOCABULARY_FILE)
if(NOT vocabulary_file)
  message(FATAL_ERROR "drvslam: src/drvslam/loop sets no DRVSLAM_DEFAULT_VOCABULARY_FILE")
endif()
get_filename_component(vocabulary_name ${vocabulary_file} NAME)
set(vocabulary_destination ${CMAKE_INSTALL_DATADIR}/drvslam)
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/drvslam/loop/default_vocabulary.cc
  DIRECTORY ${PROJECT_SOURCE_DIR}/src/drvslam/loop
  PROPERTIES COMPILE_DEFINITIONS
    "DRVSLAM_INSTALLED_VOCABULARY_PATH=\"${CMAKE_INSTALL_FULL_DATADIR}/drvslam/${vocabulary_name}\"")
set(DRVSLAM_INSTALLED_VOCABULARY "")  # relative to the prefix; empty: none trained
if(TARGET drvslam_default_vocab)
  install(FILES ${vocabulary_file} DESTINATION ${vocabulary_destination})
  set(DRVSLAM_INSTALLED_VOCABULARY ${vocabulary_destination}/${vocabulary_name})
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/drvslamConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/drvslamConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drvslam)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/drvslamConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/drvslamConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/drvslamConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drvslam)
