#include "drvslam/tools/truth/ground_truth_mapping.h"

#include <cmath>
#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/semantic/class_table.h"
#include "drvslam/tools/eval/closest_index.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"

namespace drvslam {

GroundTruthMapping MapWithGroundTruth(
    const std::string& dataset, const GroundTruthMappingOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  if (options.keyframe_every < 1) {
    throw Error("keyframe interval = " + std::to_string(options.keyframe_every) +
                " must be at least 1");
  }
  const std::string settings_path = (std::filesystem::path(dataset) / "settings.yaml").string();
  if (!std::filesystem::exists(settings_path)) throw Error(settings_path + ": missing");
  const Settings settings = LoadSettings(SettingsFile(settings_path));
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = settings.depth.depth_map_factor;
  dataset_options.expected_width = settings.camera.width;
  dataset_options.expected_height = settings.camera.height;
  const TumDataset frames(dataset, dataset_options);
  if (!frames.HasGroundTruth()) throw Error(dataset + ": no groundtruth.txt");
  const Trajectory& truth = frames.GroundTruth();
  std::vector<double> stamps;
  for (const StampedPose& pose : truth) stamps.push_back(pose.timestamp);
  GroundTruthSegmenter segmenter(dataset);
  const ClassTable classes(segmenter.ClassNames(), SegmentationOptions());

  DenseMapper mapper(settings.camera, options.dense, /*sequential=*/true);
  std::size_t total = frames.Size();
  if (options.max_frames > 0 && options.max_frames < total) total = options.max_frames;
  for (std::size_t i = 0; i < total; ++i) {
    const RgbdFrame rgbd = frames.Read(i);
    const std::size_t k = FindClosestIndex(stamps, rgbd.timestamp);
    if (std::abs(stamps[k] - rgbd.timestamp) > 1e-3) {
      throw Error(dataset + ": groundtruth.txt has no pose at " + std::to_string(rgbd.timestamp));
    }
    DenseFrame frame;
    frame.frame_id = static_cast<long>(i);
    frame.timestamp = rgbd.timestamp;
    frame.T_wc = truth[k].T_wc;
    frame.bgr = rgbd.bgr;
    frame.depth = rgbd.depth;
    const Segmentation segmentation = segmenter.Segment(rgbd.bgr, rgbd.timestamp, i);
    for (const Instance& instance : segmentation.instances) {
      DenseInstance d;
      d.mask = instance.mask;
      d.class_id = instance.class_id;
      d.track_id = instance.source_id;
      d.potentially_moving = classes.IsPotentiallyMoving(instance.class_id);
      d.key_object = classes.IsKeyObject(instance.class_id);
      d.moving = segmenter.IsMoving(instance.source_id, rgbd.timestamp);
      frame.instances.push_back(std::move(d));
    }
    if (i % static_cast<std::size_t>(options.keyframe_every) == 0) {
      mapper.AddKeyFrame(std::move(frame), nullptr);
    } else {
      mapper.AddFrame(std::move(frame));
    }
    if (progress) progress(i + 1, total);
  }
  // Keyframes near the end wait for later frames that never come: integrate them now.
  mapper.Shutdown();
  GroundTruthMapping result;
  result.cloud = mapper.Assemble();
  result.stats = mapper.Stats();
  return result;
}

}  // namespace drvslam
