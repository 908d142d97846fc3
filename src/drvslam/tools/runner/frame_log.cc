#include "drvslam/tools/runner/frame_log.h"

#include <chrono>
#include <cstdio>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/dynamic_front_end.h"

namespace drvslam {

FrameLog::FrameLog(const std::string& path) : path_(path), out_(path) {
  if (!out_) throw Error("--frame-log " + path + ": cannot write the file");
  out_ << "frame\ttimestamp\twall_s\ttrack_ms\ttracked\tkeyframes\tmap_points\trss_kib\ttrack_cpu_"
          "ms\tinliers\tkeyframe\tobjects\tmoving\tmovers_share\tfeatures\tremoved\tunlabelled\t"
          "own_masks\n";
}

void FrameLog::Append(const FrameLogLine& line) {
  const double wall_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  char text[384];
  std::snprintf(
      text, sizeof(text),
      "%zu\t%.6f\t%.3f\t%.3f\t%d\t%zu\t%zu\t%ld\t%.3f\t%d\t%d\t%d\t%d\t%.4f\t%d\t%d\t%d\t%d\n",
      line.frame, line.timestamp, wall_s, line.track_ms, line.tracked ? 1 : 0, line.keyframes,
      line.map_points, ResidentKib(), line.track_cpu_ms, line.inliers, line.keyframe ? 1 : 0,
      line.objects, line.moving, line.movers_share, line.features, line.removed, line.unlabelled,
      line.own_masks ? 1 : 0);
  out_ << text;
  out_.flush();
  if (!out_) throw Error("--frame-log " + path_ + ": write failed");
}

void AddDynamicEvents(const DynamicFrontEnd& dynamic, FrameLogLine* line) {
  const DynamicFrameReport& report = dynamic.LastReport();
  for (const ObjectEvidence& object : report.objects) {
    if (!object.potentially_moving) continue;
    ++line->objects;
    if (object.moving) ++line->moving;
  }
  line->movers_share = report.share;
  line->features = report.features_extracted;
  line->removed = static_cast<int>(report.removed_features.size());
  line->unlabelled = static_cast<int>(report.unlabelled.size());
  line->own_masks = report.own_masks;
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
