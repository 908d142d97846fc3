#include "drvslam/tools/synth/billboard.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam::synth {

std::vector<cv::Mat> LoadBillboards(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    throw Error(folder + ": billboard folder does not exist or is not a folder");
  }
  std::vector<std::string> paths;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (entry.is_regular_file(error) && ext == ".png") paths.push_back(entry.path().string());
  }
  if (error) throw Error(folder + ": cannot list the billboard folder: " + error.message());
  if (paths.empty()) throw Error(folder + ": no .png images in the billboard folder");
  std::sort(paths.begin(), paths.end());
  std::vector<cv::Mat> images;
  for (const std::string& path : paths) {
    cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (image.empty()) throw Error(path + ": cannot decode the image");
    if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257.0);
    if (image.type() != CV_8UC4) {
      throw Error(path + ": billboards need an RGBA PNG (an alpha channel marking the person)");
    }
    cv::Mat alpha;
    cv::extractChannel(image, alpha, 3);
    const cv::Rect box = cv::boundingRect(alpha >= 128);
    if (box.empty()) throw Error(path + ": the image is fully transparent");
    images.push_back(image(box).clone());
  }
  return images;
}

void AppendBillboard(int texture, double width, double height, const BillboardPlacement& placement,
                     int instance_id, TriangleList* out) {
  const Eigen::Vector3d normal(placement.facing.x(), placement.facing.y(), 0.0);
  // Seen from the front (looking along -normal), the picture's right is (-normal) x up.
  const Eigen::Vector3d right = (-normal).cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d up(placement.sway.x(), placement.sway.y(), height);
  const Eigen::Vector3d bottom_left = placement.base - 0.5 * width * right;
  const Eigen::Vector3d bottom_right = placement.base + 0.5 * width * right;
  SurfaceTag tag;
  tag.texture = texture;
  tag.instance_id = instance_id;
  tag.double_sided = true;
  AddQuad(bottom_left, bottom_right, bottom_right + up, bottom_left + up, UvRect(), tag, out);
}

}  // namespace drvslam::synth
