#include "drvslam/io/trajectory_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/io/text_lines.h"

namespace drvslam {
namespace {

std::string FormatStamp(double stamp) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", stamp);
  return text;
}

}  // namespace

Trajectory ReadTumTrajectory(const std::string& path, bool allow_empty) {
  Trajectory trajectory;
  ForEachRecord(path, 8, "8 values (timestamp tx ty tz qx qy qz qw)",
                [&](int, const std::string& where, const std::vector<std::string>& fields) {
                  double v[8];
                  ParseFiniteNumbers(fields, 8, where, v);
                  const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
                  if (q.norm() < 1e-9) throw Error(where + ": quaternion has zero length");
                  AppendStampedPose({v[0], SE3(q, Eigen::Vector3d(v[1], v[2], v[3]))}, fields[0],
                                    where, &trajectory);
                });
  if (trajectory.empty() && !allow_empty) throw Error(path + ": trajectory has no poses");
  return trajectory;
}

void AppendStampedPose(const StampedPose& pose, const std::string& stamp_field,
                       const std::string& where, Trajectory* trajectory) {
  if (!trajectory->empty() && pose.timestamp < trajectory->back().timestamp) {
    throw Error(where + ": timestamp " + stamp_field + " does not increase (previous line has " +
                FormatStamp(trajectory->back().timestamp) + ")");
  }
  // Real ground truth repeats a stamp now and then (fr2/desk line 10863: stamps rounded to
  // 0.1 ms at a 300 Hz capture rate). The TUM tools keep the later line, and so does this, so
  // the result stays strictly increasing.
  if (!trajectory->empty() && pose.timestamp == trajectory->back().timestamp) {
    trajectory->back() = pose;
  } else {
    trajectory->push_back(pose);
  }
}

std::string FormatTumPose(const StampedPose& pose) {
  Eigen::Quaterniond q = pose.T_wc.Quaternion();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d& t = pose.T_wc.Translation();
  char line[256];
  std::snprintf(line, sizeof(line), "%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f", pose.timestamp,
                t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  return line;
}

void WriteTumTrajectory(const std::string& path, const Trajectory& trajectory,
                        const std::string& header_comment) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  if (!header_comment.empty()) out << "# " << header_comment << "\n";
  out << "# timestamp tx ty tz qx qy qz qw\n";
  for (const StampedPose& pose : trajectory) out << FormatTumPose(pose) << "\n";
  out.flush();
  if (!out) throw Error(path + ": write failed");
}

}  // namespace drvslam
