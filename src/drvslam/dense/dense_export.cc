#include "drvslam/dense/dense_export.h"

#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/dense/point_cloud_io.h"

namespace drvslam {

DenseExport ExportDenseMap(DenseMapper& mapper, const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(folder, error);
  if (error || !fs::is_directory(folder)) throw Error(folder + ": cannot create output folder");
  const DenseCloud cloud = mapper.Assemble();
  DenseExport result;
  result.ply_path = (fs::path(folder) / "dense_map.ply").string();
  result.pcd_path = (fs::path(folder) / "dense_map.pcd").string();
  result.points = cloud.size();
  WritePlyCloud(result.ply_path, cloud);
  WritePcdCloud(result.pcd_path, cloud);
  return result;
}

}  // namespace drvslam
