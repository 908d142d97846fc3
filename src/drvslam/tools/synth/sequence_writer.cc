#include "drvslam/tools/synth/sequence_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

namespace fs = std::filesystem;

const char* const kFolders[] = {"rgb", "depth", "masks"};
const char* const kFiles[] = {"rgb.txt",         "depth.txt",     "associations.txt",
                              "groundtruth.txt", "instances.txt", "settings.yaml"};

// An earlier output of ours: it has instances.txt and a settings.yaml with Synth.* keys.
bool IsSyntheticSequence(const fs::path& folder) {
  std::ifstream settings(folder / "settings.yaml");
  if (!settings || !fs::is_regular_file(folder / "instances.txt")) return false;
  std::string line;
  while (std::getline(settings, line)) {
    if (line.rfind("Synth.Scenario:", 0) == 0) return true;
  }
  return false;
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  out << text;
  out.flush();
  if (!out) throw Error(path.string() + ": write failed");
}

void WritePng(const fs::path& path, const cv::Mat& image) {
  // Fastest zlib level with run-length matching: measured on 640x480 frames, a third faster
  // than the default strategy and the files come out smaller (noisy colour has few long
  // matches; depth and masks are runs).
  const std::vector<int> parameters = {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY,
                                       cv::IMWRITE_PNG_STRATEGY_RLE};
  bool ok = false;
  try {
    ok = cv::imwrite(path.string(), image, parameters);
  } catch (const cv::Exception& e) {
    throw Error(path.string() + ": cannot write the image: " + e.what());
  }
  if (!ok) throw Error(path.string() + ": cannot write the image");
}

}  // namespace

cv::Mat EncodeDepth(const cv::Mat& depth_m, double factor) {
  cv::Mat raw(depth_m.size(), CV_16UC1);
  for (int y = 0; y < depth_m.rows; ++y) {
    const float* in = depth_m.ptr<float>(y);
    uint16_t* out = raw.ptr<uint16_t>(y);
    for (int x = 0; x < depth_m.cols; ++x) {
      const double value = std::round(static_cast<double>(in[x]) * factor);
      out[x] = value >= 1.0 && value <= 65535.0 ? static_cast<uint16_t>(value) : 0;
    }
  }
  return raw;
}

void SequenceWriter::CheckFolder(const std::string& folder) {
  if (folder.empty()) throw Error("the output folder name is empty");
  std::error_code error;
  const fs::path root(folder);
  if (!fs::exists(root, error)) return;
  if (!fs::is_directory(root, error)) throw Error(folder + ": exists and is not a folder");
  if (!fs::is_empty(root, error) && !IsSyntheticSequence(root)) {
    throw Error(folder +
                ": folder is not empty and holds no earlier synthetic sequence; "
                "choose a new or empty folder");
  }
}

SequenceWriter::SequenceWriter(const std::string& folder) : folder_(folder) {
  CheckFolder(folder);
  std::error_code error;
  const fs::path root(folder);
  if (fs::exists(root, error) && !fs::is_empty(root, error)) {
    for (const char* name : kFolders) fs::remove_all(root / name, error);
    for (const char* name : kFiles) fs::remove(root / name, error);
  }
  for (const char* name : kFolders) {
    fs::create_directories(root / name, error);
    if (error) throw Error((root / name).string() + ": cannot create folder: " + error.message());
  }
}

std::string SequenceWriter::StampName(double stamp) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", stamp);
  return text;
}

void SequenceWriter::WriteFrame(double stamp, const cv::Mat& bgr, const cv::Mat& depth16,
                                const cv::Mat& mask16) const {
  const std::string name = StampName(stamp) + ".png";
  const fs::path root(folder_);
  WritePng(root / "rgb" / name, bgr);
  WritePng(root / "depth" / name, depth16);
  WritePng(root / "masks" / name, mask16);
}

void SequenceWriter::WriteLists(const Trajectory& ground_truth, const InstancesFile& instances,
                                const Settings& settings,
                                const std::string& settings_extra_yaml) const {
  const fs::path root(folder_);
  std::string rgb = "# color images\n# file: synthetic (drvslam synth)\n# timestamp filename\n";
  std::string depth = "# depth maps\n# file: synthetic (drvslam synth)\n# timestamp filename\n";
  std::string associations;
  for (const StampedPose& pose : ground_truth) {
    const std::string stamp = StampName(pose.timestamp);
    rgb += stamp + " rgb/" + stamp + ".png\n";
    depth += stamp + " depth/" + stamp + ".png\n";
    associations += stamp + " rgb/" + stamp + ".png " + stamp + " depth/" + stamp + ".png\n";
  }
  WriteText(root / "rgb.txt", rgb);
  WriteText(root / "depth.txt", depth);
  WriteText(root / "associations.txt", associations);
  WriteTumTrajectory((root / "groundtruth.txt").string(), ground_truth,
                     "ground truth trajectory (camera to world), drvslam synth");
  WriteInstancesFile((root / "instances.txt").string(), instances);
  WriteSettings(settings, (root / "settings.yaml").string(), settings_extra_yaml);
}

}  // namespace drvslam::synth
