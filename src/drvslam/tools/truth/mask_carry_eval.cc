#include "drvslam/tools/truth/mask_carry_eval.h"

#include <algorithm>
#include <functional>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/feature/orb_extractor.h"

namespace drvslam {
namespace {

const Instance* FindSource(const Segmentation& segmentation, int source_id) {
  for (const Instance& instance : segmentation.instances) {
    if (instance.source_id == source_id) return &instance;
  }
  return nullptr;
}

// `carry(k, lag, instance)` gives the instance's mask carried from frame k to k + lag, or an
// empty Mat when it expired.
std::vector<LagIoU> IoUByLag(const std::vector<Segmentation>& truth, int max_lag, int class_id,
                             int min_area,
                             const std::function<cv::Mat(int, int, const Instance&)>& carry) {
  std::vector<LagIoU> rows;
  const int frames = static_cast<int>(truth.size());
  for (int lag = 1; lag <= max_lag; ++lag) {
    LagIoU row;
    row.lag = lag;
    row.min_iou = 1.0;
    double sum = 0.0;
    for (int k = 0; k + lag < frames; ++k) {
      for (const Instance& instance : truth[k].instances) {
        if (class_id >= 0 && instance.class_id != class_id) continue;
        const Instance* later = FindSource(truth[k + lag], instance.source_id);
        if (later == nullptr || cv::countNonZero(instance.mask) < min_area ||
            cv::countNonZero(later->mask) < min_area) {
          continue;
        }
        const cv::Mat carried = carry(k, lag, instance);
        const double iou = carried.empty() ? 0.0 : MaskIoU(carried, later->mask);
        sum += iou;
        row.min_iou = std::min(row.min_iou, iou);
        ++row.samples;
      }
    }
    row.mean_iou = row.samples > 0 ? sum / row.samples : 0.0;
    if (row.samples == 0) row.min_iou = 0.0;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

std::vector<std::vector<PointMotion>> FrameToFrameTracks(const std::vector<cv::Mat>& grays,
                                                         const DynamicOptions& options) {
  const MotionConsistency consistency(options);
  OrbExtractor extractor{OrbExtractorOptions()};
  std::vector<std::vector<PointMotion>> tracks(grays.size());
  FlowImage previous_flow;
  std::vector<cv::Point2f> previous_points;
  for (std::size_t i = 0; i < grays.size(); ++i) {
    if (grays[i].type() != CV_8UC1 || grays[i].size() != grays.front().size()) {
      throw Error("FrameToFrameTracks: images must be CV_8UC1 of one size");
    }
    const FlowImage flow = BuildFlowImage(grays[i], options);
    if (i > 0) {
      std::vector<int> ids(previous_points.size());
      for (std::size_t p = 0; p < ids.size(); ++p) ids[p] = static_cast<int>(p);
      for (const FlowTrack& track : consistency.Track(previous_flow, flow, previous_points, ids)) {
        tracks[i].push_back({track.prev, track.cur});
      }
    }
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    extractor.Extract(grays[i], cv::Mat(), 0, &keypoints, &descriptors);
    previous_points.clear();
    for (const cv::KeyPoint& keypoint : keypoints) previous_points.push_back(keypoint.pt);
    previous_flow = flow;
  }
  return tracks;
}

std::vector<LagIoU> CarriedIoUByLag(const std::vector<Segmentation>& truth,
                                    const std::vector<std::vector<PointMotion>>& tracks,
                                    const ObjectMaskCarrier& carrier, int max_lag, int class_id,
                                    int min_area) {
  if (tracks.size() != truth.size()) {
    throw Error("CarriedIoUByLag: one track list per ground-truth frame is needed");
  }
  return IoUByLag(truth, max_lag, class_id, min_area,
                  [&](int k, int lag, const Instance& instance) {
                    std::vector<const std::vector<PointMotion>*> steps;
                    for (int step = 1; step <= lag; ++step) steps.push_back(&tracks[k + step]);
                    const std::vector<Instance> carried =
                        carrier.CarryThrough({instance}, steps, instance.mask.size());
                    return carried.empty() ? cv::Mat() : carried.front().mask;
                  });
}

std::vector<LagIoU> PropagatedIoUByLag(const std::vector<Segmentation>& truth,
                                       const std::vector<cv::Mat>& images,
                                       const MaskPropagator& propagator, int max_lag, int class_id,
                                       int min_area) {
  if (images.size() != truth.size()) {
    throw Error("PropagatedIoUByLag: one image per ground-truth frame is needed");
  }
  return IoUByLag(truth, max_lag, class_id, min_area,
                  [&](int k, int lag, const Instance& instance) {
                    Segmentation one;
                    one.image_size = instance.mask.size();
                    one.instances = {instance};
                    const Segmentation moved =
                        propagator.Propagate(one, images[k], images[k + lag], 0.0, k + lag);
                    return moved.instances.empty() ? cv::Mat() : moved.instances.front().mask;
                  });
}

}  // namespace drvslam
