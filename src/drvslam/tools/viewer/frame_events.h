// The frame log's events (frames.tsv, tools/runner/frame_log.h) as the report draws them beside
// the error over time: which frames were lost, skipped, made keyframes, how much of the image
// people covered and how many features the dynamic stage removed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace drvslam {

// The file `drvslam benchmark` writes into every run folder, and `drvslam run --frame-log` where
// it is pointed.
inline constexpr const char* kFrameLogFile = "frames.tsv";

// One array per column the page draws (frame, timestamp, tracked, then keyframe, inliers,
// objects, moving, movers_share, features, removed, unlabelled, own_masks where the log has
// them: logs from before the event columns have only the first three). Frames missing from the
// `frame` column were skipped (realtime). Throws Error naming the file and the line for a
// header without frame, timestamp and tracked, a line with the wrong number of fields, or a
// field that is not a number.
nlohmann::json ReadFrameEvents(const std::string& path);

}  // namespace drvslam
