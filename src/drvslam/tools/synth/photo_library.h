// PhotoLibrary: the photographs surface textures are cut from. Real photographs give ORB the
// dense, distinctive, multi-scale detail a SLAM front-end needs; without any, textures are
// painted procedurally instead (see texture_painter.h).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace drvslam::synth {

// Where Debian's opencv-doc package installs its sample photographs.
inline constexpr char kOpenCvDocDataFolder[] = "/usr/share/doc/opencv-doc/examples/data";

class PhotoLibrary {
 public:
  // No photographs: procedural textures only.
  PhotoLibrary() = default;

  // Every image in `folder` (.png .jpg .jpeg .bmp .tif .tiff, any case), sorted by file name.
  // Throws Error naming the folder when it is missing or holds no image, and naming the file
  // when one cannot be decoded or is smaller than 32x32.
  static PhotoLibrary FromFolder(const std::string& folder);
  // The photographs of the opencv-doc sample folder that suit walls and furniture: richly
  // textured, and without people (a detector must not find a person on the wallpaper). Those
  // missing are skipped; empty when the folder is absent.
  static PhotoLibrary OpenCvSamples(const std::string& folder = kOpenCvDocDataFolder);

  bool Empty() const { return photos_.empty(); }
  int Size() const { return static_cast<int>(photos_.size()); }
  const cv::Mat& Photo(int index) const { return photos_[index]; }  // CV_8UC3 BGR
  const std::vector<std::string>& Names() const { return names_; }
  // Where the photographs came from: the folder, or "procedural" when empty.
  const std::string& Source() const { return source_; }

 private:
  void Add(const std::string& path, const cv::Mat& image);

  std::vector<cv::Mat> photos_;
  std::vector<std::string> names_;
  std::string source_ = "procedural";
};

}  // namespace drvslam::synth
