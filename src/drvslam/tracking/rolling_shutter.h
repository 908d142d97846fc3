// RollingShutter: row timing of a rolling-shutter camera, for tracking. Such a camera exposes
// its rows one after another, so a moving camera sees the top and the bottom of one image from
// different poses; solved as if every row were seen at once, the pose is pulled along the motion
// by a share of what the camera moved during the readout. Before a frame is tracked, its
// keypoints are moved to where the camera would have seen them at the middle row's time (first
// order in the camera's motion over its last tracked steps). The readout time itself can be
// estimated from the tracked poses' reprojection residuals, so neither ground truth nor a
// datasheet is needed: a global-shutter camera's estimate stays near zero. docs/architecture.md.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <utility>

#include "drvslam/core/se3.h"
#include "drvslam/map/frame_features.h"

namespace drvslam {

class Frame;

// Evidence for the readout from one tracked frame's inliers: residual = (true - used) readout
// times the row's image motion, plus noise (sums of weighted products, see Observe).
struct ReadoutEvidence {
  double residual_dot_motion = 0.0;  // sum of w * e . g
  double motion_squared = 0.0;       // sum of w * g . g
  double residual_squared = 0.0;     // sum of w * e . e
  std::size_t observations = 0;
};

// The readout correction one batch of evidence asks for, if it is clear of the noise: the
// least-squares step, kept only when it is more than `min_sigmas` standard errors from zero.
std::optional<double> ReadoutStep(const ReadoutEvidence& evidence, double min_sigmas);

class RollingShutter {
 public:
  // readout_s: first row to last (negative: bottom to top), the starting value; estimate: refine
  // it from residuals.
  RollingShutter(double readout_s, bool estimate);

  double ReadoutSeconds() const { return readout_s_; }
  // Readout updates applied so far.
  int Updates() const { return updates_; }

  // A tracked step of the camera: T_current_last and the seconds between the two frames.
  void AddStep(const SE3& T_current_last, double seconds);
  // The camera's motion is unknown from here (lost, relocalized, map reset); the evidence
  // gathered towards the next update is dropped too.
  void Forget();

  // The features as the middle row would have seen them, or nullptr when there is nothing to
  // correct (no motion known yet, or a readout of 0). Records the motion Observe needs.
  std::shared_ptr<const FrameFeatures> Correct(const FrameFeatures& features);

  // Adds the residuals of a tracked frame (pose set, inlier map points in its slots) that went
  // through Correct with a known motion; keypoints without depth are left out. Every
  // kFramesPerUpdate such frames the readout is updated when the evidence is clear.
  void Observe(const Frame& frame);

  static constexpr int kStepsInMotion = 3;     // tracked steps averaged into the motion
  static constexpr int kFramesPerUpdate = 30;  // frames of evidence per readout update
  static constexpr double kMinSigmas = 3.0;    // an update must stand this far above noise
  static constexpr double kMaxReadoutS = 0.1;  // 10 Hz: no video camera reads out slower

 private:
  std::optional<Vector6d> TwistPerSecond() const;

  double readout_s_;
  bool estimate_;
  std::deque<std::pair<SE3, double>> steps_;  // oldest first
  std::optional<Vector6d> used_twist_;        // motion behind the last Correct
  ReadoutEvidence evidence_;
  int frames_in_evidence_ = 0;
  int updates_ = 0;
};

}  // namespace drvslam
