#include "drvslam/tracking/camera_acceleration.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace drvslam {
namespace {

// The long lag, where a hand-held camera's motion outweighs its poses' noise.
constexpr double kLongLagS = 0.5;
// Consecutive tracked frames further apart than this many intervals make no short sample.
constexpr double kMaxShortGapFrames = 3.0;
// The samples of the last this many seconds; each kind needs this many before it is trusted.
constexpr double kWindowS = 3.0;
constexpr std::size_t kMinSamples = 10;
// The median of a chi-square variable with 3 degrees of freedom: a squared 3-vector's median
// over this is one axis's variance.
constexpr double kChiSquare3Median = 2.366;
// Never below this share of the configured acceleration.
constexpr double kFloorShare = 0.1;

// One axis's variance from squared 3-vectors, through their median.
double AxisVariance(std::vector<double> squared_norms) {
  auto middle = squared_norms.begin() + static_cast<std::ptrdiff_t>(squared_norms.size() / 2);
  std::nth_element(squared_norms.begin(), middle, squared_norms.end());
  return *middle / kChiSquare3Median;
}

}  // namespace

Eigen::Vector3d RotationVector(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd turn(rotation);
  return turn.angle() * turn.axis();
}

CameraAccelerationEstimator::CameraAccelerationEstimator(double max_acceleration,
                                                         double max_angular_acceleration,
                                                         double frame_interval_s)
    : max_linear_(max_acceleration),
      max_angular_(max_angular_acceleration),
      frame_interval_(frame_interval_s),
      linear_(max_acceleration),
      angular_(max_angular_acceleration) {}

void CameraAccelerationEstimator::Restart() { poses_.clear(); }

void CameraAccelerationEstimator::Add(double timestamp, const SE3& T_wc) {
  poses_.push_back({timestamp, T_wc});
  while (poses_.front().timestamp < timestamp - 2.0 * kLongLagS - 2.0 * frame_interval_) {
    poses_.pop_front();
  }
  const Pose& last = poses_.back();
  const std::size_t n = poses_.size();
  if (n >= 3 &&
      last.timestamp - poses_[n - 3].timestamp <= 2.0 * kMaxShortGapFrames * frame_interval_) {
    AddSample(poses_[n - 3], poses_[n - 2], last, &consecutive_);
  }
  const Pose* middle = PoseNear(last.timestamp - kLongLagS);
  const Pose* first = middle ? PoseNear(middle->timestamp - kLongLagS) : nullptr;
  if (first != nullptr && first != middle && middle != &last) {
    AddSample(*first, *middle, last, &half_second_);
  }
  for (std::deque<Sample>* kind : {&consecutive_, &half_second_}) {
    while (!kind->empty() && kind->front().timestamp < timestamp - kWindowS) kind->pop_front();
  }
  Estimate();
}

const CameraAccelerationEstimator::Pose* CameraAccelerationEstimator::PoseNear(
    double timestamp) const {
  const Pose* nearest = nullptr;
  for (const Pose& pose : poses_) {
    if (nearest == nullptr ||
        std::abs(pose.timestamp - timestamp) < std::abs(nearest->timestamp - timestamp)) {
      nearest = &pose;
    }
  }
  if (nearest == nullptr || std::abs(nearest->timestamp - timestamp) > frame_interval_) {
    return nullptr;
  }
  return nearest;
}

void CameraAccelerationEstimator::AddSample(const Pose& first, const Pose& middle, const Pose& last,
                                            std::deque<Sample>* kind) {
  const double a = middle.timestamp - first.timestamp;
  const double b = last.timestamp - middle.timestamp;
  if (!(a > 0.0) || !(b > 0.0)) return;
  const Eigen::Vector3d centre = (last.T_wc.Translation() - middle.T_wc.Translation()) / b -
                                 (middle.T_wc.Translation() - first.T_wc.Translation()) / a;
  const Eigen::Vector3d rotation =
      RotationVector(middle.T_wc.Rotation().transpose() * last.T_wc.Rotation()) / b -
      RotationVector(first.T_wc.Rotation().transpose() * middle.T_wc.Rotation()) / a;
  const double noise_weight = 1.0 / (a * a) + std::pow(1.0 / a + 1.0 / b, 2) + 1.0 / (b * b);
  kind->push_back(
      {last.timestamp, centre.squaredNorm(), rotation.squaredNorm(), noise_weight, (a + b) / 3.0});
}

void CameraAccelerationEstimator::Estimate() {
  if (consecutive_.size() < kMinSamples || half_second_.size() < kMinSamples) return;
  // Per kind: one axis's variance v (a median), and the mean weights n, m, with
  // v = n R + m q. Two kinds, two unknowns.
  struct Kind {
    double centre, rotation, noise, motion;
  };
  const auto summarize = [](const std::deque<Sample>& samples) {
    std::vector<double> centre, rotation;
    Kind kind{0.0, 0.0, 0.0, 0.0};
    for (const Sample& sample : samples) {
      centre.push_back(sample.centre);
      rotation.push_back(sample.rotation);
      kind.noise += sample.noise_weight;
      kind.motion += sample.motion_weight;
    }
    const double count = static_cast<double>(samples.size());
    kind.centre = AxisVariance(std::move(centre));
    kind.rotation = AxisVariance(std::move(rotation));
    kind.noise /= count;
    kind.motion /= count;
    return kind;
  };
  const Kind short_kind = summarize(consecutive_);
  const Kind long_kind = summarize(half_second_);
  const double determinant =
      long_kind.motion * short_kind.noise - short_kind.motion * long_kind.noise;
  if (!(determinant > 0.0)) return;
  // q = sigma² T for a standard deviation sigma as one frame interval T sees it.
  const auto sigma = [&](double short_variance, double long_variance, double maximum) {
    const double q =
        (long_variance * short_kind.noise - short_variance * long_kind.noise) / determinant;
    const double measured = std::sqrt(std::max(0.0, q) / frame_interval_);
    return std::clamp(measured, kFloorShare * maximum, maximum);
  };
  linear_ = sigma(short_kind.centre, long_kind.centre, max_linear_);
  angular_ = sigma(short_kind.rotation, long_kind.rotation, max_angular_);
}

}  // namespace drvslam
