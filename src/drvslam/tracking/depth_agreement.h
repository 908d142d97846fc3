// DepthAgreement: whether the depth image agrees with the map's geometry at a pose. Evidence
// beyond the matched keypoints for a pose found by relocalization: every map point that should
// be visible at the pose is looked up in the depth image. A point measured where it is predicted
// agrees; one measured farther than predicted should have been seen and is not (the camera sees
// through where the map has a surface), which a wrong pose produces and a correct one does not;
// one measured nearer is hidden behind something (people, a moved chair) and is counted apart.
// Points that tracking rarely finds where they are predicted (movers that left) do not count.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/map/frame.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

struct DepthAgreementOptions {
  // A measurement agrees within max(metres, ratio * predicted depth): depth sensors' error grows
  // with distance, and map points carry their own.
  double tolerance_metres = 0.05;
  double tolerance_ratio = 0.05;
  // Frustum test of tracking: points seen at more than 60 degrees from their mean viewing
  // direction are not expected.
  double min_view_cos = 0.5;
  // Only points tracking matched in at least this share of the frames that should have seen
  // them (MapPoint::FoundRatio; points never yet predicted visible count) testify: a mover
  // mapped where it stood stays in the map after it walks off, and is then predicted visible
  // and not found, frame after frame. Without this, correct poses found again in a crowd were
  // refused for 64 frames in a row on real footage (a third of the measured points "missing").
  double min_found_ratio = 0.5;
  // Verdict: too few measured points decide nothing (the pose passes); otherwise at least this
  // share must agree and at most that share be missing.
  int min_measured = 20;
  double min_agree_share = 0.5;
  double max_missing_share = 0.25;
};

struct DepthAgreement {
  int expected = 0;    // points that should be visible at the pose
  int agree = 0;       // measured at their predicted depth
  int missing = 0;     // measured farther: should be visible and are not
  int occluded = 0;    // measured nearer: hidden behind something
  int unmeasured = 0;  // no depth at their pixel
  int Measured() const { return agree + missing + occluded; }
  double AgreeShare() const { return Measured() > 0 ? double(agree) / Measured() : 0.0; }
  double MissingShare() const { return Measured() > 0 ? double(missing) / Measured() : 0.0; }
};

// `depth`: CV_32F metres of the frame (0 = none), in the image's (distorted) pixels; empty: no
// evidence. The frame must have a pose. Points that are bad are skipped.
DepthAgreement MeasureDepthAgreement(const Frame& frame, const cv::Mat& depth,
                                     const std::vector<std::shared_ptr<MapPoint>>& points,
                                     const DepthAgreementOptions& options = {});

// False when there is enough evidence and it contradicts the pose.
bool DepthAgrees(const DepthAgreement& agreement, const DepthAgreementOptions& options = {});

}  // namespace drvslam
