#include "drvslam/io/trajectory_formats.h"

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/io/text_lines.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr char kEurocHeader[] =
    "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
    "q_RS_z []";

bool RegularFileExists(const std::string& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

// A whole field of decimal digits as nanoseconds; an Error naming `where` otherwise.
long long ParseNanoseconds(const std::string& field, const std::string& where) {
  bool digits = !field.empty();
  for (const char ch : field) digits = digits && ch >= '0' && ch <= '9';
  errno = 0;
  char* end = nullptr;
  const long long value = digits ? std::strtoll(field.c_str(), &end, 10) : 0;
  if (!digits || errno == ERANGE || *end != '\0') {
    throw Error(where + ": timestamp '" + field +
                "' is not an integer number of nanoseconds (EuRoC format)");
  }
  return value;
}

// Stamps written from microseconds divide back exactly as strtod reads the TUM text of the same
// stamp (an integer below 2^53 over 1e6, rounded once); others keep their nanoseconds.
double NanosecondsToSeconds(long long ns) {
  if (ns % 1000 == 0) return static_cast<double>(ns / 1000) / 1e6;
  return static_cast<double>(ns / 1000000000) + static_cast<double>(ns % 1000000000) / 1e9;
}

long long SecondsToNanoseconds(double seconds) { return std::llround(seconds * 1e6) * 1000; }

void WriteKitti(const std::string& path, const Trajectory& trajectory) {
  const std::string times_path = KittiTimesPath(path);
  std::ofstream poses(path);
  if (!poses) throw Error(path + ": cannot open for writing");
  std::ofstream times(times_path);
  if (!times) throw Error(times_path + ": cannot open for writing");
  for (const StampedPose& pose : trajectory) {
    const Eigen::Matrix3d r = pose.T_wc.Rotation();
    const Eigen::Vector3d& t = pose.T_wc.Translation();
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", r(0, 0), r(0, 1),
                  r(0, 2), t.x(), r(1, 0), r(1, 1), r(1, 2), t.y(), r(2, 0), r(2, 1), r(2, 2),
                  t.z());
    poses << line;
    std::snprintf(line, sizeof(line), "%.6f\n", pose.timestamp);
    times << line;
  }
  poses.flush();
  times.flush();
  if (!poses) throw Error(path + ": write failed");
  if (!times) throw Error(times_path + ": write failed");
}

void WriteEuroc(const std::string& path, const Trajectory& trajectory) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  out << kEurocHeader << "\n";
  for (const StampedPose& pose : trajectory) {
    Eigen::Quaterniond q = pose.T_wc.Quaternion();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    const Eigen::Vector3d& t = pose.T_wc.Translation();
    char line[256];
    std::snprintf(line, sizeof(line), "%lld,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f\n",
                  SecondsToNanoseconds(pose.timestamp), t.x(), t.y(), t.z(), q.w(), q.x(), q.y(),
                  q.z());
    out << line;
  }
  out.flush();
  if (!out) throw Error(path + ": write failed");
}

Trajectory ReadEuroc(const std::string& path, bool allow_empty) {
  Trajectory trajectory;
  ForEachDataLine(path, [&](int line_number, const std::vector<std::string>& fields) {
    const std::string where = path + ":" + std::to_string(line_number);
    if (fields.size() < 8) {
      throw Error(where +
                  ": expected at least 8 values (timestamp [ns], p_x, p_y, p_z, q_w, q_x, "
                  "q_y, q_z), found " +
                  std::to_string(fields.size()));
    }
    const long long ns = ParseNanoseconds(fields[0], where);
    double v[7];
    ParseFiniteNumbers({fields.begin() + 1, fields.begin() + 8}, 7, where, v);
    const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (q.norm() < 1e-9) throw Error(where + ": quaternion has zero length");
    AppendStampedPose({NanosecondsToSeconds(ns), SE3(q, Eigen::Vector3d(v[0], v[1], v[2]))},
                      fields[0], where, &trajectory);
  });
  if (trajectory.empty() && !allow_empty) throw Error(path + ": trajectory has no poses");
  return trajectory;
}

struct KittiPose {
  SE3 T_wc;
  std::string where;
};

std::vector<KittiPose> ReadKittiPoses(const std::string& path) {
  std::vector<KittiPose> poses;
  ForEachRecord(
      path, 12, "12 values (a 3x4 pose matrix, row-major)",
      [&](int, const std::string& where, const std::vector<std::string>& fields) {
        double v[12];
        ParseFiniteNumbers(fields, 12, where, v);
        Eigen::Matrix3d rotation;
        rotation << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
        // KITTI's ground truth carries 6 significant digits; a block further than this from a
        // rotation is not a pose (a shifted column, a transposed file).
        const double off =
            (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (off > 1e-4 || rotation.determinant() <= 0.0) {
          char text[128];
          std::snprintf(text, sizeof(text),
                        ": the 3x3 block is not a rotation (|R^T R - I| = %.3g, det = %.3g)", off,
                        rotation.determinant());
          throw Error(where + text);
        }
        poses.push_back({SE3(rotation, Eigen::Vector3d(v[3], v[7], v[11])), where});
      });
  return poses;
}

struct StampLine {
  double stamp;
  std::string field;
  std::string where;
};

std::vector<StampLine> ReadKittiTimes(const std::string& path) {
  std::vector<StampLine> stamps;
  ForEachRecord(path, 1, "1 value (timestamp in seconds)",
                [&](int, const std::string& where, const std::vector<std::string>& fields) {
                  const double stamp = ParseNumber(fields[0], where);
                  if (!std::isfinite(stamp)) {
                    throw Error(where + ": timestamp '" + fields[0] + "' is not finite");
                  }
                  stamps.push_back({stamp, fields[0], where});
                });
  return stamps;
}

std::string FindKittiTimes(const std::string& path, const std::string& given) {
  if (!given.empty()) return given;
  const std::string beside = KittiTimesPath(path);
  if (RegularFileExists(beside)) return beside;
  const std::string times_txt = (fs::path(path).parent_path() / "times.txt").string();
  if (RegularFileExists(times_txt)) return times_txt;
  return "";
}

Trajectory ReadKitti(const std::string& path, const std::string& times_option, bool allow_empty) {
  const std::vector<KittiPose> poses = ReadKittiPoses(path);
  if (poses.empty() && !allow_empty) throw Error(path + ": trajectory has no poses");
  const std::string times_path = FindKittiTimes(path, times_option);
  Trajectory trajectory;
  if (times_path.empty()) {
    spdlog::warn(
        "{}: KITTI poses without a times file ({} or times.txt beside it): stamped with their "
        "frame index 0, 1, 2, ...",
        path, KittiTimesPath(path));
    for (std::size_t i = 0; i < poses.size(); ++i) {
      trajectory.push_back({static_cast<double>(i), poses[i].T_wc});
    }
    return trajectory;
  }
  const std::vector<StampLine> stamps = ReadKittiTimes(times_path);
  if (stamps.size() != poses.size()) {
    throw Error(times_path + ": has " + std::to_string(stamps.size()) + " timestamps, but " + path +
                " has " + std::to_string(poses.size()) + " poses");
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    AppendStampedPose({stamps[i].stamp, poses[i].T_wc}, stamps[i].field, stamps[i].where,
                      &trajectory);
  }
  return trajectory;
}

bool IsDigits(const std::string& text) {
  if (text.empty()) return false;
  for (const char ch : text) {
    if (ch < '0' || ch > '9') return false;
  }
  return true;
}

}  // namespace

TrajectoryFormat ParseTrajectoryFormat(const std::string& name, const std::string& option) {
  if (name == "tum") return TrajectoryFormat::kTum;
  if (name == "kitti") return TrajectoryFormat::kKitti;
  if (name == "euroc") return TrajectoryFormat::kEuroc;
  throw Error(option + " = '" + name + "' must be tum, kitti or euroc");
}

std::string ToString(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::kKitti:
      return "kitti";
    case TrajectoryFormat::kEuroc:
      return "euroc";
    case TrajectoryFormat::kTum:
      break;
  }
  return "tum";
}

std::string TrajectoryFilePath(const std::string& base, TrajectoryFormat format) {
  return base + (format == TrajectoryFormat::kEuroc ? ".csv" : ".txt");
}

std::string KittiTimesPath(const std::string& pose_path) {
  const fs::path path(pose_path);
  return (path.parent_path() / (path.stem().string() + "_times.txt")).string();
}

void WriteTrajectory(const std::string& path, const Trajectory& trajectory, TrajectoryFormat format,
                     const std::string& header_comment) {
  switch (format) {
    case TrajectoryFormat::kTum:
      WriteTumTrajectory(path, trajectory, header_comment);
      return;
    case TrajectoryFormat::kKitti:
      WriteKitti(path, trajectory);
      return;
    case TrajectoryFormat::kEuroc:
      WriteEuroc(path, trajectory);
      return;
  }
}

TrajectoryFormat DetectTrajectoryFormat(const std::string& path) {
  if (!RegularFileExists(path)) {
    std::error_code error;
    if (fs::is_directory(path, error)) throw Error(path + ": is a folder, not a file");
    throw Error(path + ": file does not exist");
  }
  // The first data line decides, unless a EuRoC header comes before it; an empty file is TUM.
  TrajectoryFormat format = TrajectoryFormat::kTum;
  ForEachLine(path, [&](int line_number, const std::string& line,
                        const std::vector<std::string>& fields) {
    if (fields.empty()) return true;
    if (fields.front().front() == '#') {
      if (line.find("p_RS_R_x") == std::string::npos && line.find("[ns]") == std::string::npos) {
        return true;
      }
      format = TrajectoryFormat::kEuroc;
      return false;
    }
    const bool commas = line.find(',') != std::string::npos;
    if (fields.size() == 12) {
      format = TrajectoryFormat::kKitti;
    } else if (commas && fields.size() >= 8 && IsDigits(fields[0])) {
      format = TrajectoryFormat::kEuroc;
    } else if (fields.size() != 8) {
      throw Error(path + ":" + std::to_string(line_number) +
                  ": cannot tell the trajectory format from " + std::to_string(fields.size()) +
                  " values (tum has 8, kitti 12, euroc 8 or more comma-separated with an integer "
                  "nanosecond stamp); name the format explicitly");
    }
    return false;
  });
  return format;
}

Trajectory ReadTrajectory(const std::string& path, const TrajectoryReadOptions& options) {
  const TrajectoryFormat format = options.format ? *options.format : DetectTrajectoryFormat(path);
  switch (format) {
    case TrajectoryFormat::kKitti:
      return ReadKitti(path, options.kitti_times, options.allow_empty);
    case TrajectoryFormat::kEuroc:
      return ReadEuroc(path, options.allow_empty);
    case TrajectoryFormat::kTum:
      break;
  }
  return ReadTumTrajectory(path, options.allow_empty);
}

}  // namespace drvslam
