#include "drvslam/semantic/mask_file_segmenter.h"

#include <cctype>
#include <cstdio>
#include <filesystem>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/io/text_lines.h"
#include "drvslam/semantic/class_table.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// Frames match a timestamp-named file within this many seconds (TUM stamps carry 6 decimals;
// frames are at least ~10 ms apart).
constexpr double kStampTolerance = 1e-3;

bool AllDigits(const std::string& text) {
  if (text.empty() || text.size() > 18) return false;
  for (char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

std::string FormatStamp(double stamp) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", stamp);
  return text;
}

}  // namespace

MaskFileSegmenter::MaskFileSegmenter(const std::string& masks_dir,
                                     const SegmentationOptions& options,
                                     std::vector<std::string> frame_names)
    : dir_(masks_dir), frame_names_(std::move(frame_names)) {
  for (std::string_view name : CocoClassNames()) class_names_.emplace_back(name);
  default_class_ = CocoClassId(options.mask_class);
  if (default_class_ < 0) {
    throw Error("Segmentation.maskClass = '" + options.mask_class + "' is not a COCO class");
  }
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) throw Error(dir_ + ": mask folder does not exist");

  std::vector<fs::path> pngs;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_, ec)) {
    if (entry.is_regular_file(ec) && entry.path().extension() == ".png") {
      pngs.push_back(entry.path());
    }
  }
  if (ec) throw Error(dir_ + ": cannot list the mask folder (" + ec.message() + ")");
  if (pngs.empty()) throw Error(dir_ + ": mask folder holds no .png files");

  if (frame_names_.empty()) {
    bool any_decimal = false;
    for (const fs::path& png : pngs) {
      double stamp = 0.0;
      const std::string stem = png.stem().string();
      if (stem.find('.') != std::string::npos && ParseStamp(stem, stamp)) any_decimal = true;
    }
    by_timestamp_ = options.mask_naming == MaskNaming::kTimestamp ||
                    (options.mask_naming == MaskNaming::kAuto && any_decimal);
    for (const fs::path& png : pngs) {
      const std::string stem = png.stem().string();
      double stamp = 0.0;
      if (by_timestamp_ && ParseStamp(stem, stamp)) stamps_.Add(stamp, png.string());
      if (!by_timestamp_ && AllDigits(stem)) indices_[std::stoull(stem)] = png.string();
    }
    if (by_timestamp_ ? stamps_.Empty() : indices_.empty()) {
      throw Error(dir_ + ": no mask file is named by a " +
                  (by_timestamp_ ? "timestamp (e.g. 1305031102.175304.png)"
                                 : "frame index (e.g. 000012.png)"));
    }
  }

  for (const fs::path& candidate :
       {fs::path(dir_) / "instances.txt", fs::path(dir_).parent_path() / "instances.txt"}) {
    if (fs::is_regular_file(candidate, ec)) {
      ReadInstancesFile(candidate.string());
      break;
    }
  }
}

void MaskFileSegmenter::ReadInstancesFile(const std::string& path) {
  ForEachDataLine(path, [&](int line, const std::vector<std::string>& fields) {
    if (fields[0] == "frame") return;
    const std::size_t first = fields[0] == "instance" ? 1 : 0;
    const std::string where = path + ":" + std::to_string(line);
    if (fields.size() < first + 2 || fields.size() > first + 3) {
      throw Error(where + ": expected '[instance] ID CLASS_NAME [COCO_ID]'");
    }
    if (!AllDigits(fields[first]) || std::stoull(fields[first]) == 0 ||
        std::stoull(fields[first]) > 65535) {
      throw Error(where + ": instance id '" + fields[first] + "' must be in 1..65535");
    }
    const int id = std::stoi(fields[first]);
    int coco_id = -1;
    if (fields.size() == first + 3) {
      const double coco = ParseNumber(fields[first + 2], where);
      if (coco != static_cast<int>(coco) || coco < -1 || coco >= kCocoClassCount) {
        throw Error(where + ": COCO id '" + fields[first + 2] + "' must be in -1..79");
      }
      coco_id = static_cast<int>(coco);
    }
    const int class_id = ResolveClassId(fields[first + 1], coco_id, class_names_);
    if (!class_of_id_.emplace(id, class_id).second) {
      throw Error(where + ": instance id " + std::to_string(id) + " is listed twice");
    }
  });
}

std::string MaskFileSegmenter::Name() const { return "masks(" + dir_ + ")"; }

std::string MaskFileSegmenter::MaskPath(double timestamp, std::size_t frame_index) const {
  if (!frame_names_.empty()) {
    if (frame_index >= frame_names_.size()) {
      throw Error(dir_ + ": frame " + std::to_string(frame_index) + " is past the " +
                  std::to_string(frame_names_.size()) + " named frames");
    }
    const fs::path path =
        fs::path(dir_) / (fs::path(frame_names_[frame_index]).stem().string() + ".png");
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      throw Error(path.string() + ": no mask file for frame " + std::to_string(frame_index));
    }
    return path.string();
  }
  if (by_timestamp_) {
    if (const std::string* path = stamps_.Find(timestamp, kStampTolerance)) return *path;
    throw Error((fs::path(dir_) / (FormatStamp(timestamp) + ".png")).string() +
                ": no mask file for frame " + std::to_string(frame_index) + " (timestamp " +
                FormatStamp(timestamp) + ")");
  }
  const auto found = indices_.find(frame_index);
  if (found != indices_.end()) return found->second;
  throw Error((fs::path(dir_) / (std::to_string(frame_index) + ".png")).string() +
              ": no mask file for frame " + std::to_string(frame_index));
}

Segmentation MaskFileSegmenter::Segment(const cv::Mat& bgr, double timestamp,
                                        std::size_t frame_index) {
  RequireFrameImage(Name(), bgr, frame_index);
  const std::string path = MaskPath(timestamp, frame_index);
  Segmentation result = SegmentationFromLabelFile(path, bgr.size(), timestamp, frame_index);
  for (Instance& instance : result.instances) {
    const auto listed = class_of_id_.find(instance.source_id);
    instance.class_id = listed != class_of_id_.end() ? listed->second : default_class_;
    instance.class_name = class_names_[instance.class_id];
  }
  return result;
}

}  // namespace drvslam
