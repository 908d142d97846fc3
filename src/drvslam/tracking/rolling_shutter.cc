#include "drvslam/tracking/rolling_shutter.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "drvslam/core/rolling_shutter_model.h"
#include "drvslam/map/frame.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

std::optional<double> ReadoutStep(const ReadoutEvidence& evidence, double min_sigmas) {
  if (evidence.observations < 10 || !(evidence.motion_squared > 0)) return std::nullopt;
  const double step = evidence.residual_dot_motion / evidence.motion_squared;
  // Noise per residual component left after the fit, and the step's standard error.
  const double left =
      std::max(0.0, evidence.residual_squared - step * evidence.residual_dot_motion);
  const double noise_variance = left / (2.0 * static_cast<double>(evidence.observations) - 1.0);
  const double standard_error = std::sqrt(noise_variance / evidence.motion_squared);
  if (!std::isfinite(step) || std::abs(step) <= min_sigmas * standard_error) return std::nullopt;
  return step;
}

RollingShutter::RollingShutter(double readout_s, bool estimate)
    : readout_s_(readout_s), estimate_(estimate) {}

void RollingShutter::AddStep(const SE3& T_current_last, double seconds) {
  if (!(seconds > 0)) return;
  steps_.emplace_back(T_current_last, seconds);
  while (steps_.size() > static_cast<std::size_t>(kStepsInMotion)) steps_.pop_front();
}

void RollingShutter::Forget() {
  steps_.clear();
  used_twist_.reset();
  // Residuals gathered before a loss or a reset may come from poses that were given up.
  evidence_ = ReadoutEvidence();
  frames_in_evidence_ = 0;
}

std::optional<Vector6d> RollingShutter::TwistPerSecond() const {
  if (steps_.empty()) return std::nullopt;
  SE3 total;
  double seconds = 0.0;
  for (const auto& [step, dt] : steps_) {
    total = step * total;
    seconds += dt;
  }
  return Vector6d(total.Log() / seconds);
}

std::shared_ptr<const FrameFeatures> RollingShutter::Correct(const FrameFeatures& features) {
  used_twist_.reset();
  if (readout_s_ == 0.0 && !estimate_) return nullptr;
  used_twist_ = TwistPerSecond();
  // With no readout yet there is nothing to move; the motion is kept for Observe.
  if (!used_twist_ || readout_s_ == 0.0) return nullptr;
  return std::make_shared<const FrameFeatures>(
      features.RollingShutterCorrected(*used_twist_, readout_s_));
}

void RollingShutter::Observe(const Frame& frame) {
  if (!estimate_ || !used_twist_ || !frame.HasPose()) return;
  const FrameFeatures& features = frame.Features();
  const PinholeCamera& camera = features.Geometry().camera;
  const ScalePyramid& pyramid = features.Geometry().pyramid;
  const double height = camera.Options().height;
  const Eigen::Matrix3d R_cw = frame.Pose().Rotation();
  const Eigen::Vector3d& t_cw = frame.Pose().Translation();
  // The pose was solved with the current readout and has taken up part of any readout error, so
  // each step is short of the whole error; the steps repeat until the residuals show none.
  for (std::size_t i = 0; i < frame.Size(); ++i) {
    const std::shared_ptr<MapPoint>& point = frame.map_points[i];
    // A keypoint without depth was only rotated back (its distance is unknown), so the
    // residual model, which moves the point with the full motion, does not hold for it.
    if (!point || frame.outlier[i] || !(features.Depth(i) > 0)) continue;
    const Eigen::Vector3d X = R_cw * point->Position() + t_cw;
    if (!(X.z() > 0)) continue;
    const cv::KeyPoint& observed = features.KeypointsUn()[i];
    const Eigen::Vector2d residual =
        Eigen::Vector2d(observed.pt.x, observed.pt.y) - camera.Project(X);
    // Image motion per second of readout: the pixel's velocity as the point moves, scaled by
    // the row's time.
    const double row_time = RowTimeFromMiddle(features.Keypoints()[i].pt.y, height);
    const Eigen::Vector2d motion =
        row_time * camera.PixelVelocity(X, PointVelocity(*used_twist_, X));
    const double weight = pyramid.inv_sigma2[static_cast<std::size_t>(observed.octave)];
    evidence_.residual_dot_motion += weight * residual.dot(motion);
    evidence_.motion_squared += weight * motion.squaredNorm();
    evidence_.residual_squared += weight * residual.squaredNorm();
    ++evidence_.observations;
  }
  if (++frames_in_evidence_ < kFramesPerUpdate) return;
  if (const std::optional<double> step = ReadoutStep(evidence_, kMinSigmas)) {
    readout_s_ = std::clamp(readout_s_ + *step, -kMaxReadoutS, kMaxReadoutS);
    ++updates_;
    spdlog::debug("rolling shutter: readout {:.2f} ms (step {:+.2f} ms over {} residuals)",
                  readout_s_ * 1e3, *step * 1e3, evidence_.observations);
  }
  evidence_ = ReadoutEvidence();
  frames_in_evidence_ = 0;
}

}  // namespace drvslam
