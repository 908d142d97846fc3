// LocalizationCheck: whether a pose found again after tracking was lost may be trusted yet. A
// relocalization (or the retry against the last reference keyframe) opens a tentative window:
// the frame it found and the next ones must each track against the map and have a depth image
// that agrees with the map's geometry (depth_agreement.h); after kConfirmFrames such frames in a
// row the pose is verified. A frame that fails leaves the camera lost, with the reason counted.
// Used by the tracking thread only.
#pragma once

#include "drvslam/tracking/depth_agreement.h"
#include "drvslam/tracking/tracking_state.h"

namespace drvslam {

// Why a tentative pose was given up.
enum class LocalizationRejection { kNone, kDepthDisagrees, kNotConfirmed };

// "none", "depth disagrees" or "not confirmed".
const char* LocalizationRejectionName(LocalizationRejection rejection);

class LocalizationCheck {
 public:
  // Frames, the relocalized one included, that must pass in a row.
  static constexpr int kConfirmFrames = 3;

  // A pose was found again: the window opens.
  void Start() { confirmed_ = 0; }
  bool Pending() const { return confirmed_ < kConfirmFrames; }

  // A frame inside the window tracked against the map; `agreement` is its depth evidence.
  // False (the frame is to be lost) when the depth image contradicts the pose.
  bool Confirm(const DepthAgreement& agreement, const DepthAgreementOptions& options = {});
  // A frame inside the window could not be tracked: the pose was not confirmed.
  void Fail();

  // Quality of a frame after Confirm or Fail: lost when not tracked, tentative inside the
  // window, verified after it (and for frames tracked without any loss before them).
  LocalizationQuality Quality(bool tracked) const;

  LocalizationRejection LastRejection() const { return last_rejection_; }
  int DepthRejections() const { return depth_rejections_; }
  int UnconfirmedRejections() const { return unconfirmed_rejections_; }
  int Verified() const { return verified_; }  // windows that ended verified

 private:
  // Starts verified: the first frame of a new map is its origin.
  int confirmed_ = kConfirmFrames;
  LocalizationRejection last_rejection_ = LocalizationRejection::kNone;
  int depth_rejections_ = 0;
  int unconfirmed_rejections_ = 0;
  int verified_ = 0;
};

}  // namespace drvslam
