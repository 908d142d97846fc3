# Eclipse Cyclone DDS, optional: the ROS 2 message types (src/drvslam/ros2) need its C library
# and its IDL compiler idlc (Debian: cyclonedds-dev, cyclonedds-tools). DRVSLAM_WITH_DDS:
#   AUTO  build them when both are found, otherwise leave them out and say so;
#   ON    require both (configuration fails without them);
#   OFF   leave them out.
# Sets DRVSLAM_DDS_ENABLED and DRVSLAM_IDLC_EXECUTABLE.
set(DRVSLAM_WITH_DDS AUTO CACHE STRING
    "Build the ROS 2 message types over Cyclone DDS: AUTO, ON or OFF")
set_property(CACHE DRVSLAM_WITH_DDS PROPERTY STRINGS AUTO ON OFF)
string(TOUPPER "${DRVSLAM_WITH_DDS}" drvslam_with_dds)
if(NOT drvslam_with_dds MATCHES "^(AUTO|ON|OFF)$")
  message(FATAL_ERROR "DRVSLAM_WITH_DDS must be AUTO, ON or OFF, got '${DRVSLAM_WITH_DDS}'")
endif()

set(DRVSLAM_DDS_ENABLED OFF)
if(drvslam_with_dds STREQUAL "OFF")
  message(STATUS "Cyclone DDS: off (DRVSLAM_WITH_DDS=OFF): the ROS 2 message types and their "
                 "test are left out")
else()
  find_package(CycloneDDS 0.10 CONFIG QUIET)
  # Debian ships idlc in cyclonedds-tools; the CMake package exports no idlc target there.
  find_program(DRVSLAM_IDLC_EXECUTABLE idlc)
  set(dds_missing)
  if(NOT CycloneDDS_FOUND)
    list(APPEND dds_missing "the CycloneDDS CMake package (cyclonedds-dev)")
  endif()
  if(NOT DRVSLAM_IDLC_EXECUTABLE)
    list(APPEND dds_missing "idlc (cyclonedds-tools)")
  endif()
  if(dds_missing)
    string(REPLACE ";" " and " dds_missing "${dds_missing}")
    if(drvslam_with_dds STREQUAL "ON")
      message(FATAL_ERROR "DRVSLAM_WITH_DDS=ON but ${dds_missing}: not found. Install "
                          "cyclonedds-dev and cyclonedds-tools (scripts/install-deps.sh), or "
                          "configure with -DDRVSLAM_WITH_DDS=AUTO or OFF.")
    endif()
    message(STATUS "Cyclone DDS: ${dds_missing} not found: the ROS 2 message types and their "
                   "test are left out")
  else()
    set(DRVSLAM_DDS_ENABLED ON)
    # idlc generates C.
    enable_language(C)
    message(STATUS "Cyclone DDS ${CycloneDDS_VERSION}: building the ROS 2 message types "
                   "(idlc: ${DRVSLAM_IDLC_EXECUTABLE})")
  endif()
endif()
