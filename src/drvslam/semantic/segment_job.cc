#include "drvslam/semantic/segment_job.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <set>

#include "drvslam/core/error.h"
#include "drvslam/semantic/class_table.h"
#include "drvslam/semantic/segmentation_drawing.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

void MakeFolder(const std::string& dir, const char* option) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec)) {
    throw Error(dir + ": cannot create the " + std::string(option) + " folder");
  }
}

void WritePng(const std::string& path, const cv::Mat& image) {
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw Error(path + ": cannot write the image (" + e.err + ")");
  }
  if (!written) throw Error(path + ": cannot write the image");
}

// Writes overlays, cut-outs and JSON entries for each result; owns the output naming.
class JobOutputs {
 public:
  explicit JobOutputs(const SegmentJobOptions& options) : options_(options) {
    if (!options.overlay_dir.empty()) MakeFolder(options.overlay_dir, "--overlay");
    if (!options.cutouts_dir.empty()) MakeFolder(options.cutouts_dir, "--cutouts");
    for (const std::string& name : options.cutout_classes) {
      cutout_classes_.insert(NormalizeClassName(name));
    }
  }

  void Add(const SegmentedImage& result, const cv::Mat& bgr, SegmentJobSummary& summary) {
    const std::string name = UniqueName(result);
    if (!options_.overlay_dir.empty()) {
      WritePng((fs::path(options_.overlay_dir) / (name + ".png")).string(),
               DrawSegmentation(bgr, result.segmentation));
    }
    int number = 0;
    for (const Instance& instance : result.segmentation.instances) {
      ++number;
      nlohmann::json entry;
      entry["image"] = result.source;
      if (result.frame >= 0) entry["frame"] = result.frame;
      entry["class"] = instance.class_name;
      entry["class_id"] = instance.class_id;
      entry["score"] = instance.score;
      entry["box"] = {instance.box.x, instance.box.y, instance.box.width, instance.box.height};
      entry["mask_area"] = cv::countNonZero(instance.mask);
      json_.push_back(entry);
      if (options_.cutouts_dir.empty() ||
          cutout_classes_.count(NormalizeClassName(instance.class_name)) == 0) {
        continue;
      }
      const cv::Mat cutout = MakeCutout(bgr, instance);
      if (cutout.empty()) continue;
      std::string class_part = instance.class_name;
      for (char& c : class_part) c = c == ' ' ? '_' : c;
      WritePng((fs::path(options_.cutouts_dir) /
                (name + "_" + std::to_string(number) + "_" + class_part + ".png"))
                   .string(),
               cutout);
      ++summary.cutouts;
    }
  }

  void WriteJson() const {
    if (options_.json_path.empty()) return;
    std::ofstream out(options_.json_path);
    out << json_.dump(2) << "\n";
    if (!out) throw Error(options_.json_path + ": cannot write the JSON file");
  }

 private:
  std::string UniqueName(const SegmentedImage& result) {
    std::string name = fs::path(result.source).stem().string();
    if (result.frame >= 0) {
      char suffix[32];
      std::snprintf(suffix, sizeof(suffix), "_%06d", result.frame);
      name += suffix;
    }
    std::string unique = name;
    for (int n = 2; !used_names_.insert(unique).second; ++n) {
      unique = name + "_" + std::to_string(n);
    }
    return unique;
  }

  const SegmentJobOptions& options_;
  std::set<std::string> cutout_classes_;
  std::set<std::string> used_names_;
  nlohmann::json json_ = nlohmann::json::array();
};

}  // namespace

void SegmentJobOptions::Check() const {
  if (inputs.empty()) throw Error("segment: no input images or videos given");
  if (every < 1) throw Error("--every = " + std::to_string(every) + " must be at least 1");
  if (max_frames < 0) throw Error("--max-frames = " + std::to_string(max_frames) + " must be >= 0");
}

SegmentJobSummary RunSegmentJob(Segmenter& segmenter, const SegmentJobOptions& options,
                                const std::function<void(const SegmentedImage&)>& on_image) {
  options.Check();
  for (const std::string& input : options.inputs) {
    std::error_code ec;
    if (!fs::is_regular_file(input, ec)) throw Error(input + ": input file does not exist");
  }
  JobOutputs outputs(options);
  SegmentJobSummary summary;
  std::vector<double> times;
  std::size_t frame_counter = 0;
  const auto process = [&](const std::string& source, int frame, double timestamp,
                           const cv::Mat& bgr) {
    SegmentedImage result;
    result.source = source;
    result.frame = frame;
    const auto start = std::chrono::steady_clock::now();
    result.segmentation = segmenter.Segment(bgr, timestamp, frame_counter++);
    result.segment_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    times.push_back(result.segment_ms);
    ++summary.images;
    summary.instances += result.segmentation.instances.size();
    outputs.Add(result, bgr, summary);
    if (on_image) on_image(result);
  };

  for (const std::string& input : options.inputs) {
    cv::Mat image;
    try {
      image = cv::imread(input, cv::IMREAD_COLOR);
    } catch (const cv::Exception&) {
      image.release();
    }
    if (!image.empty()) {
      process(input, -1, 0.0, image);
      continue;
    }
    cv::VideoCapture video;
    try {
      video.open(input);
    } catch (const cv::Exception&) {
    }
    if (!video.isOpened()) throw Error(input + ": neither an image nor a video OpenCV can read");
    const double fps = video.get(cv::CAP_PROP_FPS);
    int segmented = 0;
    cv::Mat frame;
    for (int number = 0; video.read(frame) && !frame.empty(); ++number) {
      if (number % options.every != 0) continue;
      if (options.max_frames > 0 && segmented >= options.max_frames) break;
      process(input, number, fps > 0 ? number / fps : number, frame);
      ++segmented;
    }
    if (segmented == 0) throw Error(input + ": the video has no readable frames");
  }
  outputs.WriteJson();
  summary.segment_ms = SpreadOf(times);
  return summary;
}

}  // namespace drvslam
