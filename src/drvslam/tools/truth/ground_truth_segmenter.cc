#include "drvslam/tools/truth/ground_truth_segmenter.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/io/text_lines.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr double kStampTolerance = 1e-3;

std::string FormatStamp(double stamp) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", stamp);
  return text;
}

}  // namespace

GroundTruthSegmenter::GroundTruthSegmenter(const std::string& sequence_dir) : dir_(sequence_dir) {
  for (std::string_view name : CocoClassNames()) class_names_.emplace_back(name);
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) throw Error(dir_ + ": sequence folder does not exist");
  const std::string instances_path = (fs::path(dir_) / "instances.txt").string();
  if (!fs::is_regular_file(instances_path, ec)) {
    throw Error(instances_path + ": ground-truth instances file does not exist");
  }
  instances_ = ReadInstancesFile(instances_path);
  for (std::size_t i = 0; i < instances_.instances.size(); ++i) {
    const SynthInstance& instance = instances_.instances[i];
    position_of_id_[instance.id] = i;
    class_of_position_.push_back(
        ResolveClassId(instance.class_name, instance.coco_id, class_names_));
  }
  if (instances_.moving.size() != instances_.frame_stamps.size()) {
    throw Error(instances_path + ": " + std::to_string(instances_.frame_stamps.size()) +
                " frame stamps but " + std::to_string(instances_.moving.size()) +
                " rows of moving flags");
  }
  for (std::size_t f = 0; f < instances_.frame_stamps.size(); ++f) {
    frame_of_stamp_[instances_.frame_stamps[f]] = f;
  }

  const std::string rgb_list = (fs::path(dir_) / "rgb.txt").string();
  if (!fs::is_regular_file(rgb_list, ec))
    throw Error(rgb_list + ": colour image list does not exist");
  ForEachDataLine(rgb_list, [&](int line, const std::vector<std::string>& fields) {
    const std::string where = rgb_list + ":" + std::to_string(line);
    if (fields.size() < 2) throw Error(where + ": expected 'timestamp rgb/file.png'");
    const double stamp = ParseNumber(fields[0], where);
    const std::string stem = fs::path(fields[1]).stem().string();
    mask_files_.Add(stamp, (fs::path(dir_) / "masks" / (stem + ".png")).string());
  });
  if (mask_files_.Empty()) throw Error(rgb_list + ": lists no frames");
}

std::string GroundTruthSegmenter::Name() const { return "gt(" + dir_ + ")"; }

std::string GroundTruthSegmenter::MaskPath(double timestamp) const {
  if (const std::string* path = mask_files_.Find(timestamp, kStampTolerance)) return *path;
  throw Error((fs::path(dir_) / "rgb.txt").string() + ": no frame at timestamp " +
              FormatStamp(timestamp) + ", so no ground-truth mask");
}

bool GroundTruthSegmenter::IsMoving(int instance_id, double timestamp) const {
  const auto position = position_of_id_.find(instance_id);
  if (position == position_of_id_.end() || frame_of_stamp_.empty()) return false;
  auto frame = frame_of_stamp_.lower_bound(timestamp);
  if (frame == frame_of_stamp_.end() ||
      (frame != frame_of_stamp_.begin() &&
       timestamp - std::prev(frame)->first < frame->first - timestamp)) {
    frame = std::prev(frame);
  }
  if (std::abs(frame->first - timestamp) > kStampTolerance) return false;
  const std::vector<bool>& flags = instances_.moving[frame->second];
  return position->second < flags.size() && flags[position->second];
}

Segmentation GroundTruthSegmenter::Segment(const cv::Mat& bgr, double timestamp,
                                           std::size_t frame_index) {
  RequireFrameImage(Name(), bgr, frame_index);
  const std::string path = MaskPath(timestamp);
  Segmentation result = SegmentationFromLabelFile(path, bgr.size(), timestamp, frame_index);
  for (Instance& instance : result.instances) {
    const auto position = position_of_id_.find(instance.source_id);
    if (position == position_of_id_.end()) {
      throw Error(path + ": instance id " + std::to_string(instance.source_id) +
                  " is not listed in " + (fs::path(dir_) / "instances.txt").string());
    }
    instance.class_id = class_of_position_[position->second];
    instance.class_name = class_names_[instance.class_id];
  }
  return result;
}

}  // namespace drvslam
