#include "drvslam/tracking/causal_pose_filter.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace drvslam {
namespace {

// What the filter assumes of the velocity when it starts (the pose is the measurement's): a
// hand-held or robot-borne camera moves at up to a walking pace and turns at up to about a
// radian per second, so one standard deviation of each.
constexpr double kInitialSpeed = 1.0;     // m/s
constexpr double kInitialTurnRate = 1.0;  // rad/s
// Median of a chi-square variable with 6 degrees of freedom: the median of whitened squared
// 6-vectors over this is their variance scale.
constexpr double kChiSquare6Median = 5.3481;
// An innovation beyond the 99.9 % quantile of chi-square with 6 degrees of freedom is
// down-weighted to it; this many in a row (a third of a second at 30 Hz) mean the estimate has
// lost the camera: it starts again from the measurement. Fewer would restart, with a jump, where
// the tracked poses step for a few frames (real Bonn dev half, YOLO11n-seg, sequential: 3 gave a
// causal jitter of 0.49 cm and an ATE of 1.15 cm, 10 gave 0.35 and 1.10 cm).
constexpr double kInnovationGate = 22.458;
constexpr int kRejectionsToRestart = 10;
// Frames skipped while tracking was busy (--realtime on a slow or loaded machine) leave gaps of
// several frames, which the constant-velocity prediction bridges, its noise growing with the gap.
// After half a second of white acceleration (about 1 m/s^2) the velocity is uncertain by about
// 0.5 m/s, no better than unknown: a longer gap starts the filter afresh.
constexpr double kMaxGapS = 0.5;
// The inflation is measured over this many seconds of frames, once this many samples exist.
constexpr double kInflationWindowS = 3.0;
constexpr std::size_t kMinInflationSamples = 5;
// The second difference of white noise of covariance C at three frames has covariance
// C1 + 4 C2 + C3.
constexpr double kMiddleWeight = 4.0;

Eigen::Matrix3d ExpRotation(const Eigen::Vector3d& vector) {
  const double angle = vector.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, vector / angle).toRotationMatrix();
}

bool HasInformation(const Matrix6d& covariance) { return covariance.diagonal().minCoeff() > 0.0; }

double Median(std::vector<double> values) {
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

Matrix6d MeasurementCovariance(const Matrix6d& information_cw, const SE3& T_wc) {
  const Eigen::LLT<Matrix6d> factor(information_cw);
  if (factor.info() != Eigen::Success || !(information_cw.diagonal().minCoeff() > 0.0)) {
    return Matrix6d::Zero();
  }
  const Matrix6d twist_covariance = factor.solve(Matrix6d::Identity());
  // T_wc Exp(-twist): the centre moves by -R_wc rho, the orientation by -phi in the camera frame.
  Matrix6d jacobian = Matrix6d::Zero();
  jacobian.topLeftCorner<3, 3>() = -T_wc.Rotation();
  jacobian.bottomRightCorner<3, 3>() = -Eigen::Matrix3d::Identity();
  const Matrix6d covariance = jacobian * twist_covariance * jacobian.transpose();
  return 0.5 * (covariance + covariance.transpose());
}

CausalPoseFilter::CausalPoseFilter(const CausalPoseOptions& options)
    : options_(options),
      acceleration_(options.acceleration, options.angular_acceleration, options.frame_interval_s) {}

void CausalPoseFilter::Forget() {
  started_ = false;
  rebase_ = false;
  recent_.clear();
  acceleration_.Restart();
}

void CausalPoseFilter::Rebase() {
  if (started_) rebase_ = true;
  recent_.clear();
  acceleration_.Restart();
}

Matrix6d CausalPoseFilter::Floored(double timestamp, const Matrix6d& covariance) {
  const double trace = covariance.trace();
  recent_traces_.push_back({timestamp, trace});
  while (recent_traces_.front().first < timestamp - kInflationWindowS) recent_traces_.pop_front();
  std::vector<double> traces;
  for (const auto& [stamp, value] : recent_traces_) traces.push_back(value);
  const double floor = Median(std::move(traces));
  return trace < floor ? Matrix6d(covariance * (floor / trace)) : covariance;
}

CausalPose CausalPoseFilter::Update(double timestamp, const SE3& measured_T_wc,
                                    const Matrix6d& solve_covariance) {
  const Matrix6d covariance =
      HasInformation(solve_covariance) ? Floored(timestamp, solve_covariance) : solve_covariance;
  const double dt = timestamp - timestamp_;
  if (started_ && !rebase_ && (!(dt > 0) || dt > kMaxGapS)) {
    Forget();
  }
  MeasureInflation(measured_T_wc, covariance, timestamp);
  if (HasInformation(covariance)) acceleration_.Add(timestamp, measured_T_wc);
  if (HasInformation(covariance) || !started_)
    map_covariance_ = kMapShare * inflation_ * covariance;
  if (!started_) {
    Start(timestamp, measured_T_wc, covariance);
    return Estimate();
  }
  if (rebase_) {
    // The world moved by `turn`: the velocity keeps its camera-frame value.
    const Eigen::Matrix3d turn = measured_T_wc.Rotation() * rotation_.transpose();
    const Matrix12d kept = covariance_;
    const Eigen::Vector3d velocity = turn * velocity_;
    const Eigen::Vector3d angular_velocity = angular_velocity_;
    Start(timestamp, measured_T_wc, covariance);
    velocity_ = velocity;
    angular_velocity_ = angular_velocity;
    covariance_.block<3, 3>(6, 6) = turn * kept.block<3, 3>(6, 6) * turn.transpose();
    covariance_.block<3, 3>(9, 9) = kept.block<3, 3>(9, 9);
    return Estimate();
  }
  Predict(dt);
  timestamp_ = timestamp;
  if (HasInformation(covariance)) Correct(measured_T_wc, covariance);
  return Estimate();
}

void CausalPoseFilter::Start(double timestamp, const SE3& T_wc, const Matrix6d& covariance) {
  started_ = true;
  rebase_ = false;
  rejected_in_a_row_ = 0;
  timestamp_ = timestamp;
  centre_ = T_wc.Translation();
  rotation_ = T_wc.Rotation();
  velocity_.setZero();
  angular_velocity_.setZero();
  covariance_.setZero();
  covariance_.topLeftCorner<6, 6>() = inflation_ * covariance;
  covariance_.block<3, 3>(6, 6).diagonal().setConstant(kInitialSpeed * kInitialSpeed);
  covariance_.block<3, 3>(9, 9).diagonal().setConstant(kInitialTurnRate * kInitialTurnRate);
}

void CausalPoseFilter::Predict(double dt) {
  const Eigen::Matrix3d step_turn = ExpRotation(angular_velocity_ * dt);
  centre_ += velocity_ * dt;
  rotation_ = rotation_ * step_turn;
  Matrix12d transition = Matrix12d::Identity();
  transition.block<3, 3>(0, 6).diagonal().setConstant(dt);
  transition.block<3, 3>(3, 3) = step_turn.transpose();
  transition.block<3, 3>(3, 9).diagonal().setConstant(dt);
  // White acceleration of spectral density sigma² T (sigma as one frame interval T sees it).
  Matrix12d noise = Matrix12d::Zero();
  const double densities[2] = {acceleration_.Linear() * acceleration_.Linear(),
                               acceleration_.Angular() * acceleration_.Angular()};
  for (int part = 0; part < 2; ++part) {
    const double q = densities[part] * options_.frame_interval_s;
    const int pose = 3 * part;
    const int rate = 6 + 3 * part;
    noise.block<3, 3>(pose, pose).diagonal().setConstant(q * dt * dt * dt / 3.0);
    noise.block<3, 3>(pose, rate).diagonal().setConstant(q * dt * dt / 2.0);
    noise.block<3, 3>(rate, pose).diagonal().setConstant(q * dt * dt / 2.0);
    noise.block<3, 3>(rate, rate).diagonal().setConstant(q * dt);
  }
  covariance_ = transition * covariance_ * transition.transpose() + noise;
}

void CausalPoseFilter::Correct(const SE3& measured_T_wc, const Matrix6d& covariance) {
  Eigen::Matrix<double, 6, 1> innovation;
  innovation.head<3>() = measured_T_wc.Translation() - centre_;
  innovation.tail<3>() = RotationVector(rotation_.transpose() * measured_T_wc.Rotation());
  Matrix6d noise = inflation_ * covariance;
  Matrix6d innovation_covariance = covariance_.topLeftCorner<6, 6>() + noise;
  const double nis = innovation.dot(innovation_covariance.ldlt().solve(innovation));
  if (nis > kInnovationGate) {
    if (++rejected_in_a_row_ >= kRejectionsToRestart) {
      Start(timestamp_, measured_T_wc, covariance);
      return;
    }
    // Down-weighted so that it lies on the gate: one odd frame moves the estimate a little.
    noise *= nis / kInnovationGate;
    innovation_covariance = covariance_.topLeftCorner<6, 6>() + noise;
  } else {
    rejected_in_a_row_ = 0;
  }
  const Eigen::Matrix<double, 12, 6> gain =
      innovation_covariance.ldlt().solve(covariance_.leftCols<6>().transpose()).transpose();
  const Eigen::Matrix<double, 12, 1> correction = gain * innovation;
  Matrix12d keep = Matrix12d::Identity();
  keep.leftCols<6>() -= gain;
  // Joseph form: stays symmetric and positive definite.
  covariance_ = keep * covariance_ * keep.transpose() + gain * noise * gain.transpose();
  covariance_ = 0.5 * (covariance_ + covariance_.transpose());
  centre_ += correction.segment<3>(0);
  rotation_ = rotation_ * ExpRotation(correction.segment<3>(3));
  velocity_ += correction.segment<3>(6);
  angular_velocity_ += correction.segment<3>(9);
}

void CausalPoseFilter::MeasureInflation(const SE3& T_wc, const Matrix6d& covariance,
                                        double timestamp) {
  if (!HasInformation(covariance)) {
    recent_.clear();
    return;
  }
  recent_.push_back({timestamp, T_wc, covariance});
  if (recent_.size() > 3) recent_.pop_front();
  if (recent_.size() < 3) return;
  const Measured& first = recent_[0];
  const Measured& middle = recent_[1];
  const Measured& last = recent_[2];
  const double before = middle.timestamp - first.timestamp;
  const double after = last.timestamp - middle.timestamp;
  // Only evenly spaced frames one interval apart: there a second difference is the noise's.
  const double interval = options_.frame_interval_s;
  if (std::abs(before - after) > 0.25 * interval || before > 1.5 * interval) return;
  Eigen::Matrix<double, 6, 1> difference;
  difference.head<3>() =
      last.T_wc.Translation() - 2.0 * middle.T_wc.Translation() + first.T_wc.Translation();
  difference.tail<3>() = RotationVector(middle.T_wc.Rotation().transpose() * last.T_wc.Rotation()) -
                         RotationVector(first.T_wc.Rotation().transpose() * middle.T_wc.Rotation());
  differences_.push_back(
      {difference, first.covariance + kMiddleWeight * middle.covariance + last.covariance});
  const auto window = static_cast<std::size_t>(std::lround(kInflationWindowS / interval));
  while (differences_.size() > std::max<std::size_t>(window, kMinInflationSamples)) {
    differences_.pop_front();
  }
  if (differences_.size() < kMinInflationSamples) return;
  // White acceleration of density q adds (2/3) q T³ to a second difference over intervals T.
  const double t3 = interval * interval * interval;
  Eigen::Matrix<double, 6, 1> motion;
  motion.head<3>().setConstant(2.0 / 3.0 * acceleration_.Linear() * acceleration_.Linear() *
                               interval * t3);
  motion.tail<3>().setConstant(2.0 / 3.0 * acceleration_.Angular() * acceleration_.Angular() *
                               interval * t3);
  // One step of the fixed point s = s * median(whitened at s) / chi-square median per frame:
  // where the noise dominates it lands at once, and it follows the scene from there.
  std::vector<double> whitened;
  whitened.reserve(differences_.size());
  for (const SecondDifference& d : differences_) {
    Matrix6d spread = inflation_ * d.spread;
    spread.diagonal() += motion;
    whitened.push_back(d.difference.dot(spread.ldlt().solve(d.difference)));
  }
  inflation_ = std::max(1.0, inflation_ * Median(std::move(whitened)) / kChiSquare6Median);
}

CausalPose CausalPoseFilter::Estimate() const {
  CausalPose pose;
  pose.T_wc = SE3(rotation_, centre_);
  pose.linear_velocity = rotation_.transpose() * velocity_;
  pose.angular_velocity = angular_velocity_;
  Matrix6d to_world = Matrix6d::Identity();
  to_world.bottomRightCorner<3, 3>() = rotation_;
  pose.pose_covariance =
      to_world * (covariance_.topLeftCorner<6, 6>() + map_covariance_) * to_world.transpose();
  Matrix6d to_camera = Matrix6d::Identity();
  to_camera.topLeftCorner<3, 3>() = rotation_.transpose();
  pose.twist_covariance = to_camera * covariance_.bottomRightCorner<6, 6>() * to_camera.transpose();
  return pose;
}

}  // namespace drvslam
