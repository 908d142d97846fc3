#include "drvslam/io/tum_dataset.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/io/association.h"
#include "drvslam/io/depth_image.h"
#include "drvslam/io/frame_fault.h"
#include "drvslam/io/text_lines.h"

namespace drvslam {

namespace fs = std::filesystem;

struct TumDataset::SizeCache {
  std::mutex mutex;
  std::optional<cv::Size> frame0_size;  // guarded by mutex
};

namespace {

struct StampedPath {
  double stamp;
  std::string path;
};

std::string FormatValue(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

std::string FormatSize(const cv::Size& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// Non-throwing filesystem queries: a permission problem must surface as our own Error below.
bool PathExists(const std::string& path) {
  std::error_code error;
  return fs::exists(path, error);
}

bool IsFolder(const std::string& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

std::string JoinPath(const std::string& folder, const std::string& relative) {
  // An absolute listed path replaces the folder, as std::filesystem's operator/ does.
  return (fs::path(folder) / fs::path(relative)).string();
}

double ParseStamp(const std::string& field, const std::string& where) {
  const double stamp = ParseNumber(field, where);
  if (!std::isfinite(stamp)) throw Error(where + ": timestamp '" + field + "' is not finite");
  return stamp;
}

// A repeated or backward stamp: the entry is dropped (a recorder glitch must not end the run) and
// described for TumDataset::DroppedEntries. False when the stamp increases.
bool DropIfNotIncreasing(double stamp, const std::string& field, double previous, int previous_line,
                         const std::string& where, const std::string& path,
                         std::vector<FrameError>* dropped) {
  if (stamp > previous) return false;
  dropped->emplace_back(FrameFault::kTimestampNotIncreasing, path,
                        where + ": timestamp " + field + " does not increase (previous " +
                            FormatValue(previous) + " on line " + std::to_string(previous_line) +
                            "); entry skipped");
  return true;
}

void RequireFile(const std::string& path, const std::string& what) {
  if (!PathExists(path)) throw Error(path + ": " + what + " does not exist");
  if (IsFolder(path)) throw Error(path + ": " + what + " is a folder, not a file");
}

// rgb.txt / depth.txt: "timestamp path" per line; entries whose stamp does not increase over
// the last kept one are dropped into `dropped`.
std::vector<StampedPath> ReadStampList(const std::string& path, const std::string& folder,
                                       std::vector<FrameError>* dropped) {
  RequireFile(path, "image list");
  std::vector<StampedPath> list;
  int previous_line = 0;
  ForEachRecord(
      path, 2, "2 fields (timestamp image_path)",
      [&](int line_number, const std::string& where, const std::vector<std::string>& fields) {
        const double stamp = ParseStamp(fields[0], where);
        const std::string image = JoinPath(folder, fields[1]);
        if (!list.empty() && DropIfNotIncreasing(stamp, fields[0], list.back().stamp, previous_line,
                                                 where, image, dropped)) {
          return;
        }
        list.push_back({stamp, image});
        previous_line = line_number;
      });
  if (list.empty()) throw Error(path + ": lists no images");
  return list;
}

// One frame's image file: every fault is a FrameError, so a run can skip the frame.
cv::Mat LoadImage(const std::string& path, const std::string& what) {
  if (!PathExists(path)) {
    throw FrameError(FrameFault::kMissingFile, path, path + ": " + what + " does not exist");
  }
  if (IsFolder(path)) {
    throw FrameError(FrameFault::kMissingFile, path,
                     path + ": " + what + " is a folder, not a file");
  }
  std::error_code error;
  if (fs::file_size(path, error) == 0 && !error) {
    throw FrameError(FrameFault::kEmptyFile, path, path + ": " + what + " is an empty file");
  }
  cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image.empty()) {
    throw FrameError(FrameFault::kCorruptImage, path,
                     path + ": cannot decode " + what + " (corrupt or unsupported format)");
  }
  return image;
}

cv::Mat LoadColour(const std::string& path, bool rgb_order) {
  const cv::Mat raw = LoadImage(path, "colour image");
  if (raw.depth() != CV_8U) {
    throw FrameError(FrameFault::kWrongType, path,
                     path + ": colour image is " + DescribeImageType(raw) +
                         "; expected 8-bit with 1, 3 or 4 channels");
  }
  cv::Mat bgr;
  switch (raw.channels()) {
    case 1:
      cv::cvtColor(raw, bgr, cv::COLOR_GRAY2BGR);
      break;
    case 3:
      if (rgb_order) {
        cv::cvtColor(raw, bgr, cv::COLOR_RGB2BGR);
      } else {
        bgr = raw;
      }
      break;
    case 4:
      cv::cvtColor(raw, bgr, rgb_order ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
      break;
    default:
      throw FrameError(FrameFault::kWrongType, path,
                       path + ": colour image is " + DescribeImageType(raw) +
                           "; expected 8-bit with 1, 3 or 4 channels");
  }
  return bgr;
}

cv::Mat LoadDepth(const std::string& path, double depth_map_factor) {
  const cv::Mat raw = LoadImage(path, "depth image");
  if (!IsDepthImageType(raw.type())) {
    throw FrameError(FrameFault::kWrongType, path,
                     path + ": depth image is " + DescribeImageType(raw) +
                         "; expected 16-bit unsigned 1-channel (or 32-bit float 1-channel metres)");
  }
  return DepthToMetres(raw, depth_map_factor, path + ": depth image");
}

}  // namespace

void TumDatasetOptions::Check() const {
  if (!std::isfinite(depth_map_factor) || depth_map_factor <= 0.0) {
    throw Error("TumDatasetOptions.depth_map_factor must be a positive number, got " +
                FormatValue(depth_map_factor));
  }
  if (expected_width < 0) {
    throw Error("TumDatasetOptions.expected_width must be >= 0, got " +
                std::to_string(expected_width));
  }
  if (expected_height < 0) {
    throw Error("TumDatasetOptions.expected_height must be >= 0, got " +
                std::to_string(expected_height));
  }
  if ((expected_width == 0) != (expected_height == 0)) {
    throw Error(
        "TumDatasetOptions.expected_width and expected_height must both be 0 or both be set, "
        "got " +
        std::to_string(expected_width) + "x" + std::to_string(expected_height));
  }
  if (!std::isfinite(max_difference) || max_difference <= 0.0) {
    throw Error("TumDatasetOptions.max_difference must be a positive number of seconds, got " +
                FormatValue(max_difference));
  }
}

TumDataset::TumDataset(const std::string& folder, const TumDatasetOptions& options)
    : folder_(folder), options_(options), size_cache_(std::make_shared<SizeCache>()) {
  options_.Check();
  if (!PathExists(folder_)) throw Error(folder_ + ": dataset folder does not exist");
  if (!IsFolder(folder_)) throw Error(folder_ + ": dataset path is not a folder");

  const std::string associations = JoinPath(folder_, "associations.txt");
  if (PathExists(associations)) {
    RequireFile(associations, "association list");
    int previous_line = 0;
    ForEachRecord(
        associations, 4, "4 fields (t_rgb rgb_path t_depth depth_path)",
        [&](int line_number, const std::string& where, const std::vector<std::string>& fields) {
          const double rgb_stamp = ParseStamp(fields[0], where);
          const double depth_stamp = ParseStamp(fields[2], where);
          const std::string rgb_path = JoinPath(folder_, fields[1]);
          if (!entries_.empty() &&
              DropIfNotIncreasing(rgb_stamp, fields[0], entries_.back().rgb_stamp, previous_line,
                                  where, rgb_path, &dropped_)) {
            return;
          }
          entries_.push_back({rgb_stamp, depth_stamp, rgb_path, JoinPath(folder_, fields[3])});
          previous_line = line_number;
        });
    if (entries_.empty()) throw Error(associations + ": lists no frames");
  } else {
    const std::string rgb_list_path = JoinPath(folder_, "rgb.txt");
    const std::string depth_list_path = JoinPath(folder_, "depth.txt");
    if (!PathExists(rgb_list_path) || !PathExists(depth_list_path)) {
      const std::string missing = PathExists(rgb_list_path) ? depth_list_path : rgb_list_path;
      throw Error(missing +
                  ": file does not exist (a TUM sequence needs rgb.txt and depth.txt, or "
                  "associations.txt)");
    }
    const std::vector<StampedPath> rgb = ReadStampList(rgb_list_path, folder_, &dropped_);
    const std::vector<StampedPath> depth = ReadStampList(depth_list_path, folder_, &dropped_);
    std::vector<double> rgb_stamps, depth_stamps;
    for (const StampedPath& item : rgb) rgb_stamps.push_back(item.stamp);
    for (const StampedPath& item : depth) depth_stamps.push_back(item.stamp);
    const std::vector<StampMatch> matches =
        AssociateStamps(rgb_stamps, depth_stamps, 0.0, options_.max_difference);
    if (matches.empty()) {
      throw Error(rgb_list_path + " and " + depth_list_path + ": no colour/depth pair within " +
                  FormatValue(options_.max_difference) + " s");
    }
    entries_.reserve(matches.size());
    for (const StampMatch& match : matches) {
      const StampedPath& colour = rgb[match.first];
      const StampedPath& range = depth[match.second];
      entries_.push_back({colour.stamp, range.stamp, colour.path, range.path});
    }
  }

  const std::string ground_truth = JoinPath(folder_, "groundtruth.txt");
  if (PathExists(ground_truth)) ground_truth_ = ReadTumTrajectory(ground_truth);
}

std::size_t TumDataset::Size() const { return entries_.size(); }

void TumDataset::CheckIndex(std::size_t index) const {
  if (index >= entries_.size()) {
    throw Error(folder_ + ": frame index " + std::to_string(index) + " is out of range (" +
                std::to_string(entries_.size()) + " frames)");
  }
}

double TumDataset::Timestamp(std::size_t index) const {
  CheckIndex(index);
  return entries_[index].rgb_stamp;
}

cv::Size TumDataset::ReferenceSize(std::size_t index, const cv::Mat& bgr) const {
  std::lock_guard<std::mutex> lock(size_cache_->mutex);
  if (!size_cache_->frame0_size) {
    // Frame 0 defines the size whatever order frames are read in, so the outcome of Read(i) never
    // depends on which frames were read before it.
    if (index == 0) {
      size_cache_->frame0_size = bgr.size();
    } else {
      try {
        size_cache_->frame0_size =
            LoadColour(entries_[0].rgb_path, options_.rgb_is_rgb_order).size();
      } catch (const FrameError& error) {
        // Not frame `index`'s fault: no frame can be checked, so the whole dataset fails.
        throw Error(std::string(error.what()) +
                    " (the first frame sets the size of every frame; give "
                    "TumDatasetOptions.expected_width/expected_height instead)");
      }
    }
  }
  return *size_cache_->frame0_size;
}

RgbdFrame TumDataset::Read(std::size_t index) const {
  CheckIndex(index);
  const Entry& entry = entries_[index];
  RgbdFrame frame;
  frame.index = index;
  frame.timestamp = entry.rgb_stamp;
  frame.depth_timestamp = entry.depth_stamp;
  frame.rgb_path = entry.rgb_path;
  frame.depth_path = entry.depth_path;
  frame.bgr = LoadColour(entry.rgb_path, options_.rgb_is_rgb_order);
  frame.depth = LoadDepth(entry.depth_path, options_.depth_map_factor);

  cv::Size expected;
  std::string source;
  if (options_.expected_width > 0) {
    expected = cv::Size(options_.expected_width, options_.expected_height);
    source = "the expected size (TumDatasetOptions.expected_width/expected_height)";
  } else {
    expected = ReferenceSize(index, frame.bgr);
    source = "the first frame's colour image " + entries_[0].rgb_path;
  }
  if (frame.bgr.size() != expected) {
    throw FrameError(FrameFault::kWrongSize, entry.rgb_path,
                     entry.rgb_path + ": colour image is " + FormatSize(frame.bgr.size()) +
                         " but " + source + " is " + FormatSize(expected));
  }
  if (frame.depth.size() != expected) {
    throw FrameError(FrameFault::kWrongSize, entry.depth_path,
                     entry.depth_path + ": depth image is " + FormatSize(frame.depth.size()) +
                         " but " + source + " is " + FormatSize(expected));
  }
  return frame;
}

bool TumDataset::HasGroundTruth() const { return !ground_truth_.empty(); }

const Trajectory& TumDataset::GroundTruth() const { return ground_truth_; }

const std::string& TumDataset::Folder() const { return folder_; }

const std::vector<FrameError>& TumDataset::DroppedEntries() const { return dropped_; }

}  // namespace drvslam
