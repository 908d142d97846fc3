#include "drvslam/tracking/trajectory_smoother.h"

#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace drvslam {
namespace {

// Median of a chi-square variable with one degree of freedom: turns the median of squared
// Gaussian samples into their variance without letting the few wild ones decide it.
constexpr double kChiSquareMedian = 0.454936;
// The second difference of white noise of variance s² has variance 6 s².
constexpr double kSecondDifferenceVariance = 6.0;
// Evenly spaced frame triples needed before the scatter is trusted.
constexpr std::size_t kMinScatterTriples = 10;

double MedianOf(std::vector<double> values) {
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double FrameInterval(const Trajectory& trajectory, double given_s) {
  if (given_s > 0) return given_s;
  std::vector<double> intervals;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    const double dt = trajectory[i].timestamp - trajectory[i - 1].timestamp;
    if (dt > 0) intervals.push_back(dt);
  }
  return intervals.empty() ? 0.0 : MedianOf(std::move(intervals));
}

bool Finite(const StampedPose& pose) {
  return std::isfinite(pose.timestamp) && pose.T_wc.Translation().allFinite() &&
         pose.T_wc.Rotation().allFinite();
}

// The turn from pose a to pose b as a rotation vector in a's camera frame.
Eigen::Vector3d RotationStep(const SE3& a_wc, const SE3& b_wc) {
  const Eigen::AngleAxisd turn(a_wc.Rotation().transpose() * b_wc.Rotation());
  return turn.angle() * turn.axis();
}

Eigen::Matrix3d RotationFromVector(const Eigen::Vector3d& vector) {
  const double angle = vector.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, vector / angle).toRotationMatrix();
}

// Second divided difference at frame k of a stretch: c[0] x_{k-1} + c[1] x_k + c[2] x_{k+1}.
struct AccelerationRow {
  double c[3];
  double half_span;  // seconds: half of the two intervals around frame k
};

AccelerationRow RowAt(const StampedPose* poses, std::size_t k) {
  const double before = poses[k].timestamp - poses[k - 1].timestamp;
  const double after = poses[k + 1].timestamp - poses[k].timestamp;
  const double span = before + after;
  AccelerationRow row;
  row.c[0] = 2.0 / (span * before);
  row.c[2] = 2.0 / (span * after);
  row.c[1] = -(row.c[0] + row.c[2]);
  row.half_span = 0.5 * span;
  return row;
}

// One stretch's least squares over 3-vectors x_k:
//   sum_k |x_k - measured_k|²_{weights_k} + sum_k w_k |acceleration_k(x) + offset_k|²,
// where acceleration_k is the second divided difference (per component) and w_k the inverse
// variance of white acceleration over frame k's intervals (sigma² at one frame interval).
std::vector<Eigen::Vector3d> SolveStretch(const StampedPose* poses, std::size_t n,
                                          double frame_interval, double acceleration_sigma,
                                          const std::vector<Eigen::Matrix3d>& weights,
                                          const std::vector<Eigen::Vector3d>& measured,
                                          const std::vector<Eigen::Vector3d>& offsets) {
  const Eigen::Index size = static_cast<Eigen::Index>(3 * n);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
  for (std::size_t k = 0; k < n; ++k) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * k + r, 3 * k + c, weights[k](r, c));
    }
    rhs.segment<3>(static_cast<Eigen::Index>(3 * k)) = weights[k] * measured[k];
  }
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const AccelerationRow row = RowAt(poses, k);
    const double w = row.half_span / (frame_interval * acceleration_sigma * acceleration_sigma);
    for (int a = 0; a < 3; ++a) {
      const std::size_t i = k - 1 + static_cast<std::size_t>(a);
      rhs.segment<3>(static_cast<Eigen::Index>(3 * i)) -= w * row.c[a] * offsets[k];
      for (int b = 0; b < 3; ++b) {
        const std::size_t j = k - 1 + static_cast<std::size_t>(b);
        for (int d = 0; d < 3; ++d)
          entries.emplace_back(3 * i + d, 3 * j + d, w * row.c[a] * row.c[b]);
      }
    }
  }
  Eigen::SparseMatrix<double> normal(size, size);
  normal.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  const Eigen::VectorXd x = solver.solve(rhs);
  std::vector<Eigen::Vector3d> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = x.segment<3>(static_cast<Eigen::Index>(3 * k));
  return out;
}

// Inverse variances of a camera-frame scatter, as a world-frame (or body-frame) weight.
Eigen::Matrix3d WeightOf(const Eigen::Vector3d& scatter, const Eigen::Matrix3d& to_frame) {
  const Eigen::Vector3d inverse_variance = scatter.cwiseProduct(scatter).cwiseInverse();
  return to_frame * inverse_variance.asDiagonal() * to_frame.transpose();
}

void SmoothStretch(const PoseScatter& scatter, const TrajectorySmoothingOptions& options,
                   double frame_interval, const StampedPose* poses, std::size_t n,
                   StampedPose* out) {
  std::vector<Eigen::Matrix3d> position_weights(n), rotation_weights(n);
  std::vector<Eigen::Vector3d> centres(n), zeros(n, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> turn_offsets(n, Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    // The scatter is along camera axes; the centres are solved in the world frame.
    position_weights[k] = WeightOf(scatter.position_m, poses[k].T_wc.Rotation());
    rotation_weights[k] = WeightOf(scatter.rotation_rad, Eigen::Matrix3d::Identity());
    centres[k] = poses[k].T_wc.Translation();
  }
  // Rotation corrections phi_k (R_k = measured R_k exp(phi_k)): the turns between frames are
  // small, so a corrected turn is the measured one plus phi_{k+1} - phi_k, and the measured
  // turns enter each row's acceleration as an offset.
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const AccelerationRow row = RowAt(poses, k);
    turn_offsets[k] = row.c[2] * RotationStep(poses[k].T_wc, poses[k + 1].T_wc) -
                      row.c[0] * RotationStep(poses[k - 1].T_wc, poses[k].T_wc);
  }
  const std::vector<Eigen::Vector3d> smoothed_centres = SolveStretch(
      poses, n, frame_interval, options.acceleration, position_weights, centres, zeros);
  const std::vector<Eigen::Vector3d> corrections =
      SolveStretch(poses, n, frame_interval, options.angular_acceleration, rotation_weights, zeros,
                   turn_offsets);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Matrix3d rotation = poses[k].T_wc.Rotation() * RotationFromVector(corrections[k]);
    out[k].T_wc = SE3(rotation, smoothed_centres[k]);
  }
}

}  // namespace

PoseScatter MeasurePoseScatter(const Trajectory& trajectory, double frame_interval_s) {
  const double frame_interval = FrameInterval(trajectory, frame_interval_s);
  std::vector<double> position_squares[3], rotation_squares[3];
  for (std::size_t i = 1; i + 1 < trajectory.size(); ++i) {
    const StampedPose& previous = trajectory[i - 1];
    const StampedPose& current = trajectory[i];
    const StampedPose& next = trajectory[i + 1];
    if (!Finite(previous) || !Finite(current) || !Finite(next)) continue;
    const double before = current.timestamp - previous.timestamp;
    const double after = next.timestamp - current.timestamp;
    // Only evenly spaced frames one interval apart: there a second difference is the noise's.
    if (!(before > 0) || !(after > 0) || std::abs(before - after) > 0.25 * frame_interval ||
        before > 1.5 * frame_interval) {
      continue;
    }
    const Eigen::Vector3d position =
        current.T_wc.Rotation().transpose() *
        (next.T_wc.Translation() - 2.0 * current.T_wc.Translation() + previous.T_wc.Translation());
    const Eigen::Vector3d rotation =
        RotationStep(current.T_wc, next.T_wc) - RotationStep(previous.T_wc, current.T_wc);
    for (int a = 0; a < 3; ++a) {
      position_squares[a].push_back(position[a] * position[a]);
      rotation_squares[a].push_back(rotation[a] * rotation[a]);
    }
  }
  PoseScatter scatter;
  if (position_squares[0].size() < kMinScatterTriples) return scatter;
  const double scale = kChiSquareMedian * kSecondDifferenceVariance;
  for (int a = 0; a < 3; ++a) {
    scatter.position_m[a] = std::sqrt(MedianOf(position_squares[a]) / scale);
    scatter.rotation_rad[a] = std::sqrt(MedianOf(rotation_squares[a]) / scale);
  }
  return scatter;
}

Trajectory SmoothTrajectory(const Trajectory& tracked, const TrajectorySmoothingOptions& options,
                            const std::vector<std::size_t>& stretch_starts) {
  const double frame_interval = FrameInterval(tracked, options.frame_interval_s);
  const PoseScatter scatter = MeasurePoseScatter(tracked, frame_interval);
  // A zero scatter on any axis would be a pose known exactly: nothing to smooth with.
  if (!(scatter.position_m.minCoeff() > 0) || !(scatter.rotation_rad.minCoeff() > 0)) {
    return tracked;
  }
  Trajectory smoothed = tracked;
  const auto starts_here = [&](std::size_t i) {
    const double gap = tracked[i].timestamp - tracked[i - 1].timestamp;
    return !(gap > 0) || gap > kMaxGapFrames * frame_interval || !Finite(tracked[i]) ||
           !Finite(tracked[i - 1]) ||
           std::find(stretch_starts.begin(), stretch_starts.end(), i) != stretch_starts.end();
  };
  std::size_t first = 0;
  while (first < tracked.size()) {
    std::size_t end = first + 1;
    while (end < tracked.size() && !starts_here(end)) ++end;
    const std::size_t n = end - first;
    if (n >= 3) {
      SmoothStretch(scatter, options, frame_interval, &tracked[first], n, &smoothed[first]);
    }
    first = end;
  }
  return smoothed;
}

}  // namespace drvslam
