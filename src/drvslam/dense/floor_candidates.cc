#include "drvslam/dense/floor_candidates.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>

namespace drvslam {
namespace {

// Hypotheses are scored on at most this many points: ranking them needs no more, and scoring
// all of a dense map's 10^5 - 10^6 points for each of hundreds of hypotheses costs seconds.
constexpr std::size_t kScoringSample = 20000;
// RANSAC stops once it has drawn three points of the best plane so far with this probability.
constexpr double kConfidence = 0.999;

std::vector<Eigen::Vector3d> Within(const std::vector<Eigen::Vector3d>& points,
                                    const FloorPlane& plane, double distance) {
  std::vector<Eigen::Vector3d> near;
  for (const Eigen::Vector3d& p : points) {
    if (std::abs(plane.Height(p)) <= distance) near.push_back(p);
  }
  return near;
}

// Least-squares plane through `points` (normal: the covariance's smallest eigenvector), turned to
// face `up`.
FloorPlane Refit(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d normal = solver.eigenvectors().col(0).normalized();
  if (normal.dot(up) < 0.0) normal = -normal;
  FloorPlane plane;
  plane.up = normal;
  plane.offset = -normal.dot(mean);
  return plane;
}

// The hypothesis through three sampled points, near-perpendicular to `up`, with the most points
// of a random subset of `points` within inlier_distance; nothing when no hypothesis has three.
std::optional<FloorPlane> BestHypothesis(const std::vector<Eigen::Vector3d>& points,
                                         const Eigen::Vector3d& up, const FloorSearch& search,
                                         std::mt19937* random) {
  std::vector<Eigen::Vector3d> subset;
  const std::vector<Eigen::Vector3d>* scored = &points;
  if (points.size() > kScoringSample) {
    std::uniform_int_distribution<std::size_t> any(0, points.size() - 1);
    subset.reserve(kScoringSample);
    for (std::size_t i = 0; i < kScoringSample; ++i) subset.push_back(points[any(*random)]);
    scored = &subset;
  }
  const double min_cos = std::cos(search.max_tilt_deg * M_PI / 180.0);
  std::uniform_int_distribution<std::size_t> pick(0, scored->size() - 1);
  std::optional<FloorPlane> best;
  int needed = search.iterations;
  for (int i = 0; i < needed; ++i) {
    const Eigen::Vector3d& a = (*scored)[pick(*random)];
    const Eigen::Vector3d& b = (*scored)[pick(*random)];
    const Eigen::Vector3d& c = (*scored)[pick(*random)];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-9) continue;
    normal.normalize();
    if (normal.dot(up) < 0.0) normal = -normal;
    if (normal.dot(up) < min_cos) continue;
    FloorPlane hypothesis;
    hypothesis.up = normal;
    hypothesis.offset = -normal.dot(a);
    for (const Eigen::Vector3d& p : *scored) {
      if (std::abs(hypothesis.Height(p)) <= search.inlier_distance) ++hypothesis.inliers;
    }
    if (hypothesis.inliers >= 3 && (!best || hypothesis.inliers > best->inliers)) {
      best = hypothesis;
      // Enough hypotheses for three points of a plane this large to have been drawn with
      // kConfidence: a large plane is found in a few dozen.
      const double share = static_cast<double>(best->inliers) / scored->size();
      const double all_three = std::pow(share, 3.0);
      if (all_three >= 1.0) break;
      // Bounded in double before the cast: a weak first plane needs more draws than an int holds
      // (and log1p(-x) is 0 for a tiny x, which makes the quotient infinite).
      const double draws = std::ceil(std::log(1.0 - kConfidence) / std::log1p(-all_three));
      needed = static_cast<int>(std::min(static_cast<double>(search.iterations), draws));
    }
  }
  return best;
}

// Points' squares of `cell` edge on the plane orthogonal to `up`: the floor search counts area
// and connectivity in them, so the point density does not matter.
class SquareGrid {
 public:
  SquareGrid(const Eigen::Vector3d& up, double cell)
      : e1_(up.unitOrthogonal()), e2_(up.cross(e1_)), cell_(cell) {}

  std::int64_t KeyOf(const Eigen::Vector3d& p) const {
    return Key(static_cast<std::int64_t>(std::floor(e1_.dot(p) / cell_)),
               static_cast<std::int64_t>(std::floor(e2_.dot(p) / cell_)));
  }
  static std::int64_t Key(std::int64_t i, std::int64_t j) {
    return i * (std::int64_t{1} << 32) + (j & 0xffffffff);
  }
  static Eigen::Vector2d Indices(std::int64_t key) {
    const std::int64_t i = key >> 32;  // arithmetic shift: the floor of key / 2^32
    return {static_cast<double>(i),
            static_cast<double>(static_cast<std::int32_t>(key - i * (std::int64_t{1} << 32)))};
  }
  double Cell() const { return cell_; }

 private:
  Eigen::Vector3d e1_;
  Eigen::Vector3d e2_;
  double cell_;
};

bool Contains(const std::vector<std::int64_t>& sorted, std::int64_t key) {
  return std::binary_search(sorted.begin(), sorted.end(), key);
}

// The squares (sorted) of the largest 8-connected group of `points`' squares, by points: a
// hypothesis through two separate surfaces at one height is one surface or the other.
std::vector<std::int64_t> LargestConnectedSquares(const std::vector<Eigen::Vector3d>& points,
                                                  const SquareGrid& squares) {
  std::vector<std::int64_t> keys;
  keys.reserve(points.size());
  for (const Eigen::Vector3d& p : points) keys.push_back(squares.KeyOf(p));
  std::sort(keys.begin(), keys.end());
  std::vector<std::int64_t> cells;
  std::vector<std::size_t> counts;
  for (const std::int64_t key : keys) {
    if (cells.empty() || cells.back() != key) {
      cells.push_back(key);
      counts.push_back(0);
    }
    ++counts.back();
  }
  std::vector<int> group(cells.size(), -1);
  std::vector<std::size_t> group_points;
  for (std::size_t seed = 0; seed < cells.size(); ++seed) {
    if (group[seed] >= 0) continue;
    const int label = static_cast<int>(group_points.size());
    group_points.push_back(0);
    std::vector<std::size_t> stack = {seed};
    group[seed] = label;
    while (!stack.empty()) {
      const std::size_t at = stack.back();
      stack.pop_back();
      group_points[label] += counts[at];
      const Eigen::Vector2d ij = SquareGrid::Indices(cells[at]);
      for (int di = -1; di <= 1; ++di) {
        for (int dj = -1; dj <= 1; ++dj) {
          const std::int64_t key = SquareGrid::Key(static_cast<std::int64_t>(ij.x()) + di,
                                                   static_cast<std::int64_t>(ij.y()) + dj);
          const auto found = std::lower_bound(cells.begin(), cells.end(), key);
          if (found == cells.end() || *found != key) continue;
          const std::size_t next = static_cast<std::size_t>(found - cells.begin());
          if (group[next] < 0) {
            group[next] = label;
            stack.push_back(next);
          }
        }
      }
    }
  }
  const int largest = static_cast<int>(std::max_element(group_points.begin(), group_points.end()) -
                                       group_points.begin());
  std::vector<std::int64_t> kept;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (group[i] == largest) kept.push_back(cells[i]);
  }
  return kept;
}

// Whether `p` lies in one of `squares_kept` or next to one (its noisy edge).
bool NearSquares(const Eigen::Vector3d& p, const SquareGrid& squares,
                 const std::vector<std::int64_t>& squares_kept) {
  const Eigen::Vector2d ij = SquareGrid::Indices(squares.KeyOf(p));
  for (int di = -1; di <= 1; ++di) {
    for (int dj = -1; dj <= 1; ++dj) {
      if (Contains(squares_kept, SquareGrid::Key(static_cast<std::int64_t>(ij.x()) + di,
                                                 static_cast<std::int64_t>(ij.y()) + dj))) {
        return true;
      }
    }
  }
  return false;
}

// Area of `cells`, and their mean width: the area over the length along their long axis. k
// squares in a row have centres of variance (k^2 - 1) / 12 squares^2 along it. A band bent
// round a corner (a slice of two walls) is as narrow by this measure as a straight one.
void MeasureExtent(const std::vector<std::int64_t>& cells, double cell, FloorCandidate* candidate) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const std::int64_t key : cells) mean += SquareGrid::Indices(key);
  mean /= static_cast<double>(cells.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const std::int64_t key : cells) {
    const Eigen::Vector2d d = SquareGrid::Indices(key) - mean;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(cells.size());
  const double along = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance).eigenvalues()(1);
  const double length = cell * std::sqrt(12.0 * std::max(along, 0.0) + 1.0);
  candidate->area = static_cast<double>(cells.size()) * cell * cell;
  candidate->width = candidate->area / length;
}

}  // namespace

std::vector<FloorCandidate> HorizontalPlanes(std::vector<Eigen::Vector3d> points,
                                             const Eigen::Vector3d& up,
                                             const Eigen::Vector3d& camera,
                                             const FloorSearch& search) {
  std::vector<FloorCandidate> found;
  std::mt19937 random(20240601u);  // fixed: --sequential runs give the same grid
  const std::size_t least = std::max<std::size_t>(search.min_inliers, 3);
  const SquareGrid squares(up, search.area_cell);
  const double min_cos = std::cos(search.max_tilt_deg * M_PI / 180.0);
  // Each round takes one plane away: a candidate, or a steep one a sampled plane across a wall
  // refitted to.
  for (int round = 0; round < 2 * search.max_candidates + 2 && points.size() >= least &&
                      static_cast<int>(found.size()) < search.max_candidates;
       ++round) {
    const std::optional<FloorPlane> sampled = BestHypothesis(points, up, search, &random);
    if (!sampled) break;
    const std::vector<std::int64_t> kept =
        LargestConnectedSquares(Within(points, *sampled, search.inlier_distance), squares);
    const auto on_surface = [&](const Eigen::Vector3d& p, const FloorPlane& plane,
                                double distance) {
      return std::abs(plane.Height(p)) <= distance && NearSquares(p, squares, kept);
    };
    std::vector<Eigen::Vector3d> inliers;
    for (const Eigen::Vector3d& p : points) {
      if (on_surface(p, *sampled, search.inlier_distance)) inliers.push_back(p);
    }
    if (inliers.size() < least) break;
    // The sampled plane passes through three noisy points; all its inliers place it better.
    FloorPlane plane = Refit(inliers, up);
    inliers.clear();
    for (const Eigen::Vector3d& p : points) {
      if (on_surface(p, plane, search.inlier_distance)) inliers.push_back(p);
    }
    if (inliers.size() < least) break;
    plane.inliers = inliers.size();
    if (plane.up.dot(up) >= min_cos) {
      FloorCandidate candidate;
      candidate.plane = plane;
      candidate.depth_below_camera = plane.Height(camera);
      MeasureExtent(kept, search.area_cell, &candidate);
      found.push_back(candidate);
    }
    const double band = search.removal_bands * search.inlier_distance;
    points.erase(
        std::remove_if(points.begin(), points.end(),
                       [&](const Eigen::Vector3d& p) { return on_surface(p, plane, band); }),
        points.end());
  }
  return found;
}

}  // namespace drvslam
