#include "drvslam/tracking/trajectory_smoother.h"

#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <vector>

namespace drvslam {
namespace {

// Median of a chi-square variable with one degree of freedom: turns the median of squared
// Gaussian samples into their variance without letting the few wild ones decide it.
constexpr double kChiSquareMedian = 0.454936;
// The second difference of white noise of variance s² has variance 6 s².
constexpr double kSecondDifferenceVariance = 6.0;
constexpr std::size_t kMinScatterSamples = 30;

double MedianFrameInterval(const Trajectory& trajectory) {
  std::vector<double> intervals;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    const double dt = trajectory[i].timestamp - trajectory[i - 1].timestamp;
    if (dt > 0) intervals.push_back(dt);
  }
  if (intervals.empty()) return 0.0;
  auto middle = intervals.begin() + static_cast<std::ptrdiff_t>(intervals.size() / 2);
  std::nth_element(intervals.begin(), middle, intervals.end());
  return *middle;
}

double Median(std::vector<double> values) {
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
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

// Frames i-1, i, i+1 belong to one stretch when neither gap is longer than kMaxGapFrames.
bool Joined(const Trajectory& t, std::size_t i, double frame_interval) {
  const double before = t[i].timestamp - t[i - 1].timestamp;
  const double after = t[i + 1].timestamp - t[i].timestamp;
  const double longest = kMaxGapFrames * frame_interval;
  return before > 0 && after > 0 && before <= longest && after <= longest;
}

// The smoothing problem of one stretch [first, first + n): minimise
//   sum_i |x_i - measured_i|² / scatter² + sum_i w_i |acceleration_i(x)|²,
// where acceleration_i is the second divided difference at frame i and w_i the inverse variance
// of the mean of white acceleration over that frame's interval.
class StretchSmoother {
 public:
  StretchSmoother(const Trajectory& t, std::size_t first, std::size_t n, double frame_interval)
      : t_(t), first_(first), n_(n), frame_interval_(frame_interval) {}

  // Normal equations for one kind of state (positions or rotation corrections).
  void Factorize(double scatter, double acceleration_sigma) {
    std::vector<Eigen::Triplet<double>> entries;
    const double measurement_weight = 1.0 / (scatter * scatter);
    for (std::size_t k = 0; k < n_; ++k) entries.emplace_back(k, k, measurement_weight);
    weights_.assign(n_, 0.0);
    for (std::size_t k = 1; k + 1 < n_; ++k) {
      const Row row = RowAt(k);
      weights_[k] = row.half_span / (frame_interval_ * acceleration_sigma * acceleration_sigma);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          entries.emplace_back(k - 1 + a, k - 1 + b, weights_[k] * row.c[a] * row.c[b]);
        }
      }
    }
    Eigen::SparseMatrix<double> normal(static_cast<Eigen::Index>(n_),
                                       static_cast<Eigen::Index>(n_));
    normal.setFromTriplets(entries.begin(), entries.end());
    solver_.compute(normal);
    measurement_weight_ = measurement_weight;
  }

  // Smoothed camera centres.
  std::vector<Eigen::Vector3d> Positions() const {
    Eigen::MatrixXd rhs(n_, 3);
    for (std::size_t k = 0; k < n_; ++k) {
      rhs.row(k) = measurement_weight_ * t_[first_ + k].T_wc.Translation().transpose();
    }
    const Eigen::MatrixXd x = solver_.solve(rhs);
    std::vector<Eigen::Vector3d> out(n_);
    for (std::size_t k = 0; k < n_; ++k) out[k] = x.row(k).transpose();
    return out;
  }

  // Rotation corrections phi_k (R_k = measured R_k * exp(phi_k)). The turns between frames are
  // small, so a turn with corrections is the measured turn plus phi_{k+1} - phi_k.
  std::vector<Eigen::Vector3d> RotationCorrections() const {
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n_, 3);
    for (std::size_t k = 1; k + 1 < n_; ++k) {
      const Row row = RowAt(k);
      const Eigen::Vector3d before = RotationStep(Pose(k - 1).T_wc, Pose(k).T_wc);
      const Eigen::Vector3d after = RotationStep(Pose(k).T_wc, Pose(k + 1).T_wc);
      // The measured turns' share of the row's acceleration.
      const Eigen::Vector3d offset = row.c[2] * after - row.c[0] * before;
      for (int a = 0; a < 3; ++a) rhs.row(k - 1 + a) -= weights_[k] * row.c[a] * offset.transpose();
    }
    const Eigen::MatrixXd x = solver_.solve(rhs);
    std::vector<Eigen::Vector3d> out(n_);
    for (std::size_t k = 0; k < n_; ++k) out[k] = x.row(k).transpose();
    return out;
  }

 private:
  // Second divided difference at frame k: c[0] x_{k-1} + c[1] x_k + c[2] x_{k+1}.
  struct Row {
    double c[3];
    double half_span;
  };
  Row RowAt(std::size_t k) const {
    const double before = Pose(k).timestamp - Pose(k - 1).timestamp;
    const double after = Pose(k + 1).timestamp - Pose(k).timestamp;
    const double span = before + after;
    Row row;
    row.c[0] = 2.0 / (span * before);
    row.c[2] = 2.0 / (span * after);
    row.c[1] = -(row.c[0] + row.c[2]);
    row.half_span = 0.5 * span;
    return row;
  }
  const StampedPose& Pose(std::size_t k) const { return t_[first_ + k]; }

  const Trajectory& t_;
  std::size_t first_, n_;
  double frame_interval_;
  double measurement_weight_ = 0.0;
  std::vector<double> weights_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace

PoseScatter MeasurePoseScatter(const Trajectory& trajectory) {
  const double frame_interval = MedianFrameInterval(trajectory);
  std::vector<double> position_squares, rotation_squares;
  for (std::size_t i = 1; i + 1 < trajectory.size(); ++i) {
    if (!Joined(trajectory, i, frame_interval)) continue;
    const double before = trajectory[i].timestamp - trajectory[i - 1].timestamp;
    const double after = trajectory[i + 1].timestamp - trajectory[i].timestamp;
    // Only evenly spaced frames: there a second difference is the noise's and not the gap's.
    if (std::abs(before - after) > 0.25 * std::min(before, after)) continue;
    const Eigen::Vector3d position = trajectory[i + 1].T_wc.Translation() -
                                     2.0 * trajectory[i].T_wc.Translation() +
                                     trajectory[i - 1].T_wc.Translation();
    const Eigen::Vector3d rotation = RotationStep(trajectory[i].T_wc, trajectory[i + 1].T_wc) -
                                     RotationStep(trajectory[i - 1].T_wc, trajectory[i].T_wc);
    for (int a = 0; a < 3; ++a) {
      position_squares.push_back(position[a] * position[a]);
      rotation_squares.push_back(rotation[a] * rotation[a]);
    }
  }
  PoseScatter scatter;
  if (position_squares.size() < kMinScatterSamples) return scatter;
  const double scale = kChiSquareMedian * kSecondDifferenceVariance;
  scatter.position_m = std::sqrt(Median(position_squares) / scale);
  scatter.rotation_rad = std::sqrt(Median(rotation_squares) / scale);
  return scatter;
}

Trajectory SmoothTrajectory(const Trajectory& tracked, const TrajectorySmoothingOptions& options) {
  const PoseScatter scatter = MeasurePoseScatter(tracked);
  if (!(scatter.position_m > 0) || !(scatter.rotation_rad > 0)) return tracked;
  const double frame_interval = MedianFrameInterval(tracked);
  Trajectory smoothed = tracked;
  std::size_t first = 0;
  while (first < tracked.size()) {
    std::size_t end = first + 1;
    while (end < tracked.size()) {
      const double gap = tracked[end].timestamp - tracked[end - 1].timestamp;
      if (!(gap > 0) || gap > kMaxGapFrames * frame_interval) break;
      ++end;
    }
    const std::size_t n = end - first;
    if (n >= 3) {
      StretchSmoother stretch(tracked, first, n, frame_interval);
      stretch.Factorize(scatter.position_m, options.acceleration);
      const std::vector<Eigen::Vector3d> centres = stretch.Positions();
      stretch.Factorize(scatter.rotation_rad, options.angular_acceleration);
      const std::vector<Eigen::Vector3d> corrections = stretch.RotationCorrections();
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Matrix3d rotation =
            tracked[first + k].T_wc.Rotation() * RotationFromVector(corrections[k]);
        smoothed[first + k].T_wc = SE3(rotation, centres[k]);
      }
    }
    first = end;
  }
  return smoothed;
}

}  // namespace drvslam
