// FrameLog: `drvslam run --frame-log FILE`, one tab-separated line per tracked frame, for
// finding stalls (the tracking thread's time per frame next to the wall clock at which the
// loop-closing log lines say corrections ran) and for soak runs (map size and resident memory
// against the frame count). Columns: frame (index in the sequence), timestamp, wall_s (seconds
// since the Unix epoch when TrackRGBD returned, the clock of the log lines), track_ms (the
// TrackRGBD call), tracked (0/1), keyframes, map_points, rss_kib (VmRSS of the process),
// track_cpu_ms (the tracking thread's CPU time in that call: a frame whose track_ms is far above
// it waited for a core, one whose CPU time is high had more work), then the frame's events, to
// put beside its error over time: inliers (map points its pose was estimated from), keyframe
// (0/1: it became one), and from the dynamic stage (all 0 without it): objects (instances of
// potentially-moving classes), moving (those judged moving), movers_share (image share of
// potentially-moving objects), features (extracted), removed, unlabelled (regions found by
// geometry alone), own_masks (0/1: the frame's own masks, not carried ones).
#pragma once

#include <cstddef>
#include <fstream>
#include <string>

namespace drvslam {

struct FrameLogLine {
  std::size_t frame = 0;
  double timestamp = 0.0;
  double track_ms = 0.0;
  double track_cpu_ms = 0.0;
  bool tracked = false;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  int inliers = 0;
  bool keyframe = false;
  int objects = 0;
  int moving = 0;
  double movers_share = 0.0;
  int features = 0;
  int removed = 0;
  int unlabelled = 0;
  bool own_masks = false;
};

class DynamicFrontEnd;
// Fills the dynamic stage's columns of `line` from its last frame's report.
void AddDynamicEvents(const DynamicFrontEnd& dynamic, FrameLogLine* line);

class FrameLog {
 public:
  // Throws Error naming the file when it cannot be written.
  explicit FrameLog(const std::string& path);
  void Append(const FrameLogLine& line);

 private:
  std::string path_;
  std::ofstream out_;
};

// The process's resident set size in KiB (VmRSS of /proc/self/status); 0 where unavailable.
long ResidentKib();

}  // namespace drvslam
