// FrameLog: `drvslam run --frame-log FILE`, one tab-separated line per tracked frame, for
// finding stalls (the tracking thread's time per frame next to the wall clock at which the
// loop-closing log lines say corrections ran) and for soak runs (map size and resident memory
// against the frame count). Columns: frame (index in the sequence), timestamp, wall_s (seconds
// since the Unix epoch when TrackRGBD returned, the clock of the log lines), track_ms (the
// TrackRGBD call), tracked (0/1), keyframes, map_points, rss_kib (VmRSS of the process),
// track_cpu_ms (the tracking thread's CPU time in that call: a frame whose track_ms is far above
// it waited for a core, one whose CPU time is high had more work).
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
};

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
