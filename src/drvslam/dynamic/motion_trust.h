// When to believe unlabelled motion. Moving points outside every potentially-moving mask have
// no semantic reason to move; a real camera makes a static scene break the motion tests too
// (motion blur, rolling shutter, depth misregistered to colour, calibration a few percent off).
// So, per frame, before such points become removed regions:
//  - a blurred frame (frame_sharpness.h) gives no unlabelled evidence (also with a map-anchored
//    pose: without the veto the real Bonn crowd dev half went from 5.0 to 23.0 cm, geometry
//    alone, sequential);
//  - a scene model that explains too few of the static pairs (Dynamic.minInlierShare) gives
//    none: the model, not the world, failed;
//  - a track moves only when its residual also exceeds Dynamic.residualFactor times the median
//    residual of the static pairs under the same test, so loosely fitting frames raise the bar;
//  - when more than Dynamic.maxUnlabelledShare of the tracks that should be still move, the
//    camera model failed. With a map-anchored pose (motion_consistency.h) those are the anchored
//    tracks outside the masks: the map's static points, which blur or a bad calibration break
//    and a crowd does not. Without one, all tested tracks outside the masks: a "mover" covering
//    most of a scene with no semantic reason to move is then taken for the camera's error.
// In a frame whose thresholds were raised, what passes is still only a candidate:
// motion_persistence.h wants it in Dynamic.unlabelledFrames consecutive frames.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/dynamic/motion_consistency.h"

namespace drvslam {

enum class UnlabelledVerdict {
  kTrusted,        // the evidence may form regions
  kBlurred,        // the frame is blurred
  kMisfit,         // the scene model explains too few static pairs
  kCameraFailure,  // too much of the unlabelled scene "moves"
};
const char* UnlabelledVerdictName(UnlabelledVerdict verdict);

struct UnlabelledEvidence {
  UnlabelledVerdict verdict = UnlabelledVerdict::kTrusted;
  // Inlier share of the test that judges most tracks: the frame-to-frame pose's where it was
  // fitted, else the fundamental matrix's or homography's. -1: no model.
  double inlier_share = -1.0;
  // Thresholds in force for unlabelled motion (pixels): the configured ones, raised to
  // Dynamic.residualFactor times the static pairs' median residual.
  double epipolar_threshold = 0.0;
  double reprojection_threshold = 0.0;
  int tested = 0;  // tracks outside the masks with a test
  int moving = 0;  // of them, moving under the raised thresholds
  // The share the camera-failure rule weighs: of the anchored tested tracks with a map-anchored
  // pose, else moving / tested.
  double moving_share = 0.0;
  // The input tracks with their moving flags under the raised thresholds (FindUnlabelledMotion's
  // input); empty unless the verdict is kTrusted.
  std::vector<FlowTrack> tracks;
};

// motion: this frame's motion consistency. labelled: empty or CV_8UC1 of the image size
// (nonzero = potentially-moving masks; tracks ending there are not unlabelled). blurred: the
// frame's sharpness judgement. Throws drvslam::Error on a bad mask type.
UnlabelledEvidence WeighUnlabelledEvidence(const MotionConsistencyResult& motion,
                                           const cv::Mat& labelled, bool blurred,
                                           const DynamicOptions& options);

}  // namespace drvslam
