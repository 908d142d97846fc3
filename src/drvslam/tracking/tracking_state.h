// TrackingState: where tracking stands after a frame. Apart from tracker.h so that the public
// API (system.h) can name it without the tracker's internals.
#pragma once

namespace drvslam {

enum class TrackingState { kNotInitialized, kOk, kLost };

// "not initialized", "ok" or "lost" (defined in tracker.cc).
const char* TrackingStateName(TrackingState state);

}  // namespace drvslam
