// FrameObserver: a hook that sees every frame System::TrackRGBD finished, with what tracking
// already has at hand (the result, the image, the instance masks and which features were kept),
// for a viewer or a recorder. OnFrame runs on the tracking thread at the end of TrackRGBD, so it
// must only copy or take references and return: encoding, drawing and sending belong on the
// observer's own thread. Its time is recorded as the stage "observer" in stats.json.
#pragma once

#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/system.h"

namespace drvslam {

struct DynamicFrameReport;
class FrameFeatures;

// Valid during OnFrame only: copy (or reference-count) what is kept.
struct FrameObservation {
  const TrackResult* track = nullptr;
  // The caller's colour image (CV_8UC3 BGR or CV_8UC1); the caller may reuse its buffer after
  // TrackRGBD returns, so an observer that keeps it clones it.
  const cv::Mat* bgr = nullptr;
  // The features tracking used (after dynamic removal); null when the frame was rejected.
  std::shared_ptr<const FrameFeatures> features;
  // The dynamic stage's decisions for the frame (masks, object states, kept and removed
  // features); null when dynamic handling is off.
  const DynamicFrameReport* dynamic = nullptr;
  double frame_ms = 0.0;  // the whole TrackRGBD call, the observer excluded
  // Milliseconds of each stage that recorded a time for this frame (extraction, tracking,
  // segmentation_wait, removal, ...; stages of other threads appear with their latest value).
  std::map<std::string, double> stage_ms;
  std::size_t frames = 0;   // frames tracked so far (this one included), lost ones counted
  std::size_t tracked = 0;  // of them, tracked
};

class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  virtual void OnFrame(const FrameObservation& observation) = 0;
};

}  // namespace drvslam
