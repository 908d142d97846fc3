#include "drvslam/tools/eval/rpe.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/tools/eval/closest_index.h"
#include "drvslam/tools/eval/error_statistics.h"

namespace drvslam {
namespace {

// The script keys poses by stamp in a dict: sorted, one pose per stamp, the later line winning.
struct KeyedPoses {
  std::vector<double> stamps;
  std::vector<Eigen::Matrix4d> poses;
};

KeyedPoses SortedByStamp(const Trajectory& trajectory) {
  std::vector<std::size_t> order(trajectory.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return trajectory[a].timestamp < trajectory[b].timestamp;
  });
  KeyedPoses keyed;
  for (const std::size_t index : order) {
    const StampedPose& pose = trajectory[index];
    if (!keyed.stamps.empty() && keyed.stamps.back() == pose.timestamp) {
      keyed.poses.back() = pose.T_wc.Matrix();
      continue;
    }
    keyed.stamps.push_back(pose.timestamp);
    keyed.poses.push_back(pose.T_wc.Matrix());
  }
  return keyed;
}

// Inverse of a rigid 4x4 transform (any scale sits in the translation only).
Eigen::Matrix4d RigidInverse(const Eigen::Matrix4d& T) {
  Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();
  inverse.topLeftCorner<3, 3>() = T.topLeftCorner<3, 3>().transpose();
  inverse.topRightCorner<3, 1>() = -T.topLeftCorner<3, 3>().transpose() * T.topRightCorner<3, 1>();
  return inverse;
}

// The script's ominus(a, b) = inv(a) * b.
Eigen::Matrix4d Ominus(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return RigidInverse(a) * b;
}

double RotationAngleOf(const Eigen::Matrix4d& T) {
  const double cosine = (T.topLeftCorner<3, 3>().trace() - 1.0) / 2.0;
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t half = values.size() / 2;
  return values.size() % 2 == 1 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

// The script's sanity check that the two trajectories overlap in time: map each estimate stamp
// to its nearest ground-truth stamp and back, and count the distinct estimate stamps reached.
std::size_t OverlappingStamps(const std::vector<double>& gt, const std::vector<double>& est,
                              double offset) {
  std::set<double> reached;
  for (const double t_est : est) {
    const double t_gt = gt[FindClosestIndex(gt, t_est + offset)];
    reached.insert(est[FindClosestIndex(est, t_gt - offset)]);
  }
  return reached.size();
}

}  // namespace

void RpeOptions::Check() const {
  if (!std::isfinite(delta) || delta <= 0.0) {
    std::ostringstream message;
    message << "--rpe-delta must be a positive number of seconds, got " << delta;
    throw Error(message.str());
  }
  if (!std::isfinite(offset)) throw Error("--offset must be a finite number of seconds");
  if (!std::isfinite(scale) || scale <= 0.0) {
    std::ostringstream message;
    message << "RPE scale must be positive, got " << scale;
    throw Error(message.str());
  }
}

namespace {

// ComputeRpe up to the pair count check: `compared` may hold fewer than 2 pairs, the statistics
// are then left at 0.
RpeResult ComparePosePairs(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
  options.Check();
  if (gt.empty()) throw Error("RPE: the ground-truth trajectory has no poses");
  if (est.empty()) throw Error("RPE: the estimated trajectory has no poses");
  const KeyedPoses gt_keyed = SortedByStamp(gt);
  const KeyedPoses est_keyed = SortedByStamp(est);
  const std::vector<double>& gt_stamps = gt_keyed.stamps;
  const std::vector<double>& est_stamps = est_keyed.stamps;

  const std::size_t overlapping = OverlappingStamps(gt_stamps, est_stamps, options.offset);
  if (overlapping < 2) {
    throw Error("RPE: too few overlapping stamps between ground truth and estimate (" +
                std::to_string(overlapping) + "); are these the same sequence?");
  }

  const std::size_t n = est_stamps.size();
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = FindClosestIndex(est_stamps, est_stamps[i] + options.delta);
    if (j != n - 1) pairs.emplace_back(i, j);
  }

  // The overlap check above guarantees at least 2 ground-truth stamps.
  std::vector<double> gt_intervals;
  for (std::size_t k = 1; k < gt_stamps.size(); ++k) {
    gt_intervals.push_back(gt_stamps[k] - gt_stamps[k - 1]);
  }
  const double max_gt_gap = 2.0 * Median(gt_intervals);

  RpeResult result;
  result.delta = options.delta;
  std::vector<double> trans_errors;
  std::vector<double> rot_errors;
  for (const auto& [i, j] : pairs) {
    const double est_0 = est_stamps[i] + options.offset;
    const double est_1 = est_stamps[j] + options.offset;
    const std::size_t g0 = FindClosestIndex(gt_stamps, est_0);
    const std::size_t g1 = FindClosestIndex(gt_stamps, est_1);
    if (std::abs(gt_stamps[g0] - est_0) > max_gt_gap ||
        std::abs(gt_stamps[g1] - est_1) > max_gt_gap) {
      continue;
    }
    Eigen::Matrix4d est_motion = Ominus(est_keyed.poses[j], est_keyed.poses[i]);
    est_motion.topRightCorner<3, 1>() *= options.scale;
    const Eigen::Matrix4d gt_motion = Ominus(gt_keyed.poses[g1], gt_keyed.poses[g0]);
    const Eigen::Matrix4d error = Ominus(est_motion, gt_motion);

    RpePair pair;
    pair.est_stamp_0 = est_stamps[i];
    pair.est_stamp_1 = est_stamps[j];
    pair.gt_stamp_0 = gt_stamps[g0];
    pair.gt_stamp_1 = gt_stamps[g1];
    pair.trans_error = error.topRightCorner<3, 1>().norm();
    pair.rot_error = RotationAngleOf(error);
    trans_errors.push_back(pair.trans_error);
    rot_errors.push_back(pair.rot_error);
    result.compared.push_back(pair);
  }
  if (result.compared.size() < 2) return result;

  constexpr double kDegreesPerRadian = 180.0 / M_PI;
  const ErrorStatistics trans = ComputeErrorStatistics(trans_errors);
  const ErrorStatistics rot = ComputeErrorStatistics(rot_errors);
  result.pairs = result.compared.size();
  result.trans_rmse = trans.rmse;
  result.trans_mean = trans.mean;
  result.rot_rmse_deg = rot.rmse * kDegreesPerRadian;
  result.rot_mean_deg = rot.mean * kDegreesPerRadian;
  return result;
}

}  // namespace

RpeResult ComputeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
  RpeResult result = ComparePosePairs(gt, est, options);
  if (result.compared.size() < 2) {
    std::ostringstream message;
    message << "RPE: only " << result.compared.size() << " pose pair(s) " << options.delta
            << " s apart have ground truth; at least 2 are needed (is the estimate shorter than "
               "--rpe-delta?)";
    throw Error(message.str());
  }
  return result;
}

std::optional<RpeResult> ComputeRpeIfLongEnough(const Trajectory& gt, const Trajectory& est,
                                                const RpeOptions& options) {
  RpeResult result = ComparePosePairs(gt, est, options);
  if (result.compared.size() < 2) return std::nullopt;
  return result;
}

}  // namespace drvslam
