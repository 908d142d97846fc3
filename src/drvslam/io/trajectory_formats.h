// Trajectory files in the three formats SLAM tools exchange, all camera-to-world (T_wc):
//   tum:   "timestamp tx ty tz qx qy qz qw" per line, seconds (trajectory_io.h).
//   kitti: "r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz" per line: the top 3x4 block of T_wc,
//          row-major, as the KITTI odometry poses/NN.txt. The format has no timestamps, so they
//          go to a times file beside it (one stamp in seconds per line, as KITTI's times.txt).
//   euroc: CSV with the header of EuRoC's state_groundtruth_estimate0/data.csv, "#timestamp,
//          p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z []",
//          then "ns,px,py,pz,qw,qx,qy,qz" per line: integer nanoseconds, quaternion w first.
//          EuRoC's own files give the IMU body's pose and 9 more columns (velocity, biases);
//          drvslam writes the camera's pose and the 8 pose columns, and reads both.
// Readers are strict like ReadTumTrajectory: a bad line is an Error naming the file and line.
#pragma once

#include <optional>
#include <string>

#include "drvslam/io/trajectory_io.h"

namespace drvslam {

enum class TrajectoryFormat { kTum, kKitti, kEuroc };

// "tum", "kitti" or "euroc"; anything else is an Error naming `option` (e.g.
// "--trajectory-format").
TrajectoryFormat ParseTrajectoryFormat(const std::string& name, const std::string& option);
std::string ToString(TrajectoryFormat format);

// The file a trajectory named `base` (a path without extension, e.g. OUT/CameraTrajectory) is
// written to: base.txt for tum and kitti, base.csv for euroc.
std::string TrajectoryFilePath(const std::string& base, TrajectoryFormat format);
// The times file that goes with a KITTI pose file: "<folder>/<stem>_times.txt".
std::string KittiTimesPath(const std::string& pose_path);

// Writes `trajectory` to `path` in `format` (kitti: also KittiTimesPath(path)). Stamps keep the
// microseconds TUM writes (6 decimals; euroc: that many nanoseconds), poses 9 decimals, so each
// format reads back to the same poses within 1e-9. `header_comment` goes on a '#' line in tum
// files only (KITTI tools take no comments; the EuRoC header is fixed). Throws Error when a
// file cannot be written.
void WriteTrajectory(const std::string& path, const Trajectory& trajectory, TrajectoryFormat format,
                     const std::string& header_comment = "");

// The format of a trajectory file, from its content: a comment naming EuRoC's columns
// ("p_RS_R_x" or "[ns]"), else the first data line: 12 values: kitti; comma-separated with an
// integer first value and 8 or more values: euroc; 8 values: tum. Anything else is an Error
// naming the file and line; a file without data lines is tum.
TrajectoryFormat DetectTrajectoryFormat(const std::string& path);

struct TrajectoryReadOptions {
  std::optional<TrajectoryFormat> format;  // nullopt: DetectTrajectoryFormat
  // kitti: the times file. Empty: KittiTimesPath(path) if it exists, else times.txt in the same
  // folder if it exists, else the poses are stamped with their frame index (0, 1, 2, ...; a
  // warning says so), which associates them only with another trajectory stamped that way.
  std::string kitti_times;
  bool allow_empty = false;  // a file without poses is an Error unless set
};

// Reads a trajectory in any of the three formats. Like ReadTumTrajectory, a repeated stamp
// replaces the previous pose and a stamp that goes back is an Error naming the file and line;
// so are malformed lines, non-finite values, zero quaternions, KITTI rotation blocks that are
// not rotations, and a KITTI times file whose count differs from the poses'.
Trajectory ReadTrajectory(const std::string& path, const TrajectoryReadOptions& options = {});

}  // namespace drvslam
