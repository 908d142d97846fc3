// Trajectories in the TUM RGB-D format: one pose per line, "timestamp tx ty tz qx qy qz qw",
// camera-to-world (T_wc), '#' comments. Reading is strict: a malformed line, a NaN, a zero
// quaternion or a timestamp that goes backwards is an Error naming the file and line.
#pragma once

#include <string>
#include <vector>

#include "drvslam/core/se3.h"

namespace drvslam {

struct StampedPose {
  double timestamp = 0.0;  // seconds
  SE3 T_wc;
};

using Trajectory = std::vector<StampedPose>;

// Reads a TUM trajectory. Fields may be separated by spaces, tabs or commas (as the TUM tools
// accept). A line that repeats the previous line's timestamp replaces that pose, as the TUM tools
// do (real ground truth has such lines), so the result's stamps strictly increase. An empty file
// (no poses) is an Error unless allow_empty is set.
Trajectory ReadTumTrajectory(const std::string& path, bool allow_empty = false);

// Appends a pose read from `where` (file:line) to a trajectory being read: a stamp below the
// last one is an Error naming `where` and `stamp_field` (the stamp as written); an equal stamp
// replaces the last pose (the TUM tools' rule). Shared by the readers of every format.
void AppendStampedPose(const StampedPose& pose, const std::string& stamp_field,
                       const std::string& where, Trajectory* trajectory);

// Writes timestamps with 6 decimals and pose values with 9, so reading back reproduces the
// written numbers (the timestamp and translation exactly; the quaternion to 1e-9, since reading
// renormalizes it). The quaternion is written with qw >= 0. Throws Error when the file
// cannot be written.
void WriteTumTrajectory(const std::string& path, const Trajectory& trajectory,
                        const std::string& header_comment = "");

// Formats one pose line as WriteTumTrajectory does (without the newline).
std::string FormatTumPose(const StampedPose& pose);

}  // namespace drvslam
