#include "drvslam/tools/synth/photo_library.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

namespace fs = std::filesystem;

// Photographs larger than this are shrunk on loading: patches are cut at about one photo pixel
// per texel, so more resolution only costs memory.
constexpr int kMaxPhotoSide = 1024;
constexpr int kMinPhotoSide = 32;

bool IsImageFile(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" ||
         ext == ".tiff";
}

cv::Mat ReadPhoto(const std::string& path) {
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) throw Error(path + ": cannot decode the image");
  if (image.cols < kMinPhotoSide || image.rows < kMinPhotoSide) {
    throw Error(path + ": image is smaller than " + std::to_string(kMinPhotoSide) + "x" +
                std::to_string(kMinPhotoSide));
  }
  return image;
}

}  // namespace

void PhotoLibrary::Add(const std::string& path, const cv::Mat& image) {
  cv::Mat photo = image;
  const int side = std::max(image.cols, image.rows);
  if (side > kMaxPhotoSide) {
    const double scale = static_cast<double>(kMaxPhotoSide) / side;
    cv::resize(image, photo, cv::Size(), scale, scale, cv::INTER_AREA);
  }
  photos_.push_back(photo);
  names_.push_back(fs::path(path).filename().string());
}

PhotoLibrary PhotoLibrary::FromFolder(const std::string& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    throw Error(folder + ": texture folder does not exist or is not a folder");
  }
  std::vector<std::string> paths;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    if (entry.is_regular_file(error) && IsImageFile(entry.path())) {
      paths.push_back(entry.path().string());
    }
  }
  if (error) throw Error(folder + ": cannot list the texture folder: " + error.message());
  if (paths.empty()) {
    throw Error(folder + ": no images (.png .jpg .jpeg .bmp .tif .tiff) in the texture folder");
  }
  std::sort(paths.begin(), paths.end());
  PhotoLibrary library;
  for (const std::string& path : paths) library.Add(path, ReadPhoto(path));
  library.source_ = folder;
  return library;
}

PhotoLibrary PhotoLibrary::OpenCvSamples(const std::string& folder) {
  // Chosen by eye: dense detail at several scales, no large flat areas, no people, and no two
  // views of the same subject (graf3, leuvenB), which would look like a false loop closure.
  static const char* const kNames[] = {"baboon.jpg",       "board.jpg",        "building.jpg",
                                       "fruits.jpg",       "graf1.png",        "home.jpg",
                                       "leuvenA.jpg",      "aero1.jpg",        "aero3.jpg",
                                       "starry_night.jpg", "rubberwhale1.png", "squirrel_cls.jpg",
                                       "butterfly.jpg",    "box_in_scene.png", "left.jpg"};
  PhotoLibrary library;
  std::error_code error;
  if (!fs::is_directory(folder, error)) return library;
  for (const char* name : kNames) {
    const std::string path = (fs::path(folder) / name).string();
    if (!fs::is_regular_file(path, error)) continue;
    const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty() || image.cols < kMinPhotoSide || image.rows < kMinPhotoSide) continue;
    library.Add(path, image);
  }
  if (!library.Empty()) library.source_ = folder;
  return library;
}

}  // namespace drvslam::synth
