#include "drvslam/tools/viewer/viewer_json.h"

#include <array>
#include <cstdint>
#include <cstring>

#include "drvslam/core/error.h"
#include "drvslam/tools/eval/ate.h"

namespace drvslam {

std::string Base64(const void* data, std::size_t bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((bytes + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes; i += 3) {
    const std::uint32_t v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  const std::size_t rest = bytes - i;
  if (rest > 0) {
    std::uint32_t v = in[i] << 16;
    if (rest == 2) v |= in[i + 1] << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

nlohmann::json PoseJson(const StampedPose& pose) {
  const Eigen::Vector3d& t = pose.T_wc.Translation();
  const Eigen::Quaterniond& q = pose.T_wc.Quaternion();
  return nlohmann::json::array({pose.timestamp, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()});
}

nlohmann::json TrajectoryJson(const Trajectory& trajectory) {
  nlohmann::json poses = nlohmann::json::array();
  for (const StampedPose& pose : trajectory) poses.push_back(PoseJson(pose));
  return poses;
}

DenseCloud Decimate(const DenseCloud& cloud, std::size_t budget) {
  if (cloud.size() <= budget) return cloud;
  DenseCloud kept;
  kept.reserve(budget);
  for (std::size_t k = 0; k < budget; ++k) kept.push_back(cloud[k * cloud.size() / budget]);
  return kept;
}

nlohmann::json CloudJson(const DenseCloud& cloud, std::size_t total, bool with_colors) {
  // The page reads these as little-endian typed arrays; x86 and ARM Linux are little-endian.
  std::vector<float> positions;
  positions.reserve(cloud.size() * 3);
  std::vector<std::uint8_t> colors;
  if (with_colors) colors.reserve(cloud.size() * 3);
  for (const DensePoint& p : cloud) {
    positions.insert(positions.end(), {p.position.x(), p.position.y(), p.position.z()});
    if (with_colors) colors.insert(colors.end(), {p.r, p.g, p.b});
  }
  nlohmann::json json = {{"count", cloud.size()},
                         {"total", total},
                         {"positions", Base64(positions.data(), positions.size() * sizeof(float))}};
  if (with_colors) json["colors"] = Base64(colors.data(), colors.size());
  return json;
}

nlohmann::json GridJson(const OccupancyGrid& grid) {
  std::vector<std::uint8_t> cells;
  cells.reserve(grid.cells.size());
  for (GridCell cell : grid.cells) cells.push_back(static_cast<std::uint8_t>(cell));
  nlohmann::json pose = nlohmann::json::array();
  for (int i = 0; i < 16; ++i) pose.push_back(grid.T_world_grid(i / 4, i % 4));
  return {{"width", grid.width},           {"height", grid.height},
          {"resolution", grid.resolution}, {"origin", {grid.origin.x(), grid.origin.y()}},
          {"T_world_grid", pose},          {"cells", Base64(cells.data(), cells.size())}};
}

std::optional<TruthOverlay> OverlayTruth(const Trajectory& ground_truth, const Trajectory& estimate,
                                         std::string* why) {
  AteResult ate;
  try {
    ate = ComputeAte(ground_truth, estimate, AteOptions());
  } catch (const Error& error) {
    if (why) *why = error.what();
    return std::nullopt;
  }
  // The alignment maps the estimate onto the ground truth: p_gt = s R p_est + t.
  const Alignment& a = ate.alignment;
  const Eigen::Matrix3d R_inverse = a.R.transpose();
  TruthOverlay overlay;
  overlay.ground_truth = nlohmann::json::array();
  for (const StampedPose& pose : ground_truth) {
    const Eigen::Vector3d p = R_inverse * (pose.T_wc.Translation() - a.t) / a.scale;
    overlay.ground_truth.push_back({pose.timestamp, p.x(), p.y(), p.z()});
  }
  overlay.errors = nlohmann::json::array();
  for (const AteMatch& match : ate.matches)
    overlay.errors.push_back({match.est_stamp, match.error});
  overlay.rmse = ate.errors.rmse;
  overlay.matched = ate.matched;
  return overlay;
}

}  // namespace drvslam
