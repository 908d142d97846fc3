// TrackingState: where tracking stands after a frame. Apart from tracker.h so that the public
// API (system.h) can name it without the tracker's internals.
#pragma once

namespace drvslam {

enum class TrackingState { kNotInitialized, kOk, kLost };

// "not initialized", "ok" or "lost" (defined in tracker.cc).
const char* TrackingStateName(TrackingState state);

// How far a frame's pose may be trusted (tracking/localization_check.h). Verified: tracked
// without a loss, or found again and confirmed (consecutive frames tracked against the map, the
// depth image agreeing with the map's geometry). Tentative: found again and not confirmed yet;
// a pose off by a whole repeat of the scene is only possible here. Lost: no pose.
enum class LocalizationQuality { kLost, kTentative, kVerified };

// "lost", "tentative" or "verified" (defined in localization_check.cc).
const char* LocalizationQualityName(LocalizationQuality quality);

}  // namespace drvslam
