#include "drvslam/tools/runner/frame_log.h"

#include <chrono>
#include <cstdio>
#include <sstream>

#include "drvslam/core/error.h"

namespace drvslam {

FrameLog::FrameLog(const std::string& path) : path_(path), out_(path) {
  if (!out_) throw Error("--frame-log " + path + ": cannot write the file");
  out_ << "frame\ttimestamp\twall_s\ttrack_ms\ttracked\tkeyframes\tmap_points\trss_kib\ttrack_cpu_"
          "ms\n";
}

void FrameLog::Append(const FrameLogLine& line) {
  const double wall_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  char text[256];
  std::snprintf(text, sizeof(text), "%zu\t%.6f\t%.3f\t%.3f\t%d\t%zu\t%zu\t%ld\t%.3f\n", line.frame,
                line.timestamp, wall_s, line.track_ms, line.tracked ? 1 : 0, line.keyframes,
                line.map_points, ResidentKib(), line.track_cpu_ms);
  out_ << text;
  out_.flush();
  if (!out_) throw Error("--frame-log " + path_ + ": write failed");
}

long ResidentKib() {
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (status == nullptr) return 0;
  char line[256];
  long kib = 0;
  while (std::fgets(line, sizeof(line), status) != nullptr) {
    if (std::sscanf(line, "VmRSS: %ld kB", &kib) == 1) break;
  }
  std::fclose(status);
  return kib;
}

}  // namespace drvslam
