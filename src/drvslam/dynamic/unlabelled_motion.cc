#include "drvslam/dynamic/unlabelled_motion.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/lower_median.h"
#include "drvslam/core/pixel_index.h"

namespace drvslam {
namespace {

struct MovingPoint {
  cv::Point2f p;
  float depth;
  int track;
};

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Flood-fill mask values: pixels the growth may not enter, and those it reached.
constexpr uint8_t kBlocked = 1;
constexpr uint8_t kGrown = 255;

// The growth margin around a group at depth `z`: the pixel margin, or the metric reach seen at
// that depth when it is larger.
int GrowthMargin(double z, double focal_px, const DynamicOptions& options) {
  double margin = options.region_margin;
  if (focal_px > 0.0 && options.region_reach > 0.0 && z > 0.0) {
    margin = std::max(margin, focal_px * options.region_reach / z);
  }
  return static_cast<int>(std::ceil(margin));
}

}  // namespace

std::vector<MovingRegion> FindUnlabelledMotion(const std::vector<FlowTrack>& tracks,
                                               const cv::Mat& labelled, const cv::Mat& depth,
                                               const DynamicOptions& options, double focal_px) {
  if (depth.empty() || depth.type() != CV_32FC1) {
    throw Error("FindUnlabelledMotion: depth must be CV_32FC1 metres");
  }
  if (!labelled.empty() && (labelled.type() != CV_8UC1 || labelled.size() != depth.size())) {
    throw Error("FindUnlabelledMotion: the labelled mask must be CV_8UC1 of the depth's size");
  }
  std::vector<MovingPoint> points;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const FlowTrack& track = tracks[t];
    if (!track.MovingBest()) continue;
    cv::Point pixel;
    if (!PixelIndex(track.cur, &pixel)) continue;
    const int x = pixel.x;
    const int y = pixel.y;
    if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) continue;
    if (!labelled.empty() && labelled.at<uint8_t>(y, x) != 0) continue;
    const float z = depth.at<float>(y, x);
    if (!(z > 0.0f) || !std::isfinite(z)) continue;
    points.push_back({track.cur, z, static_cast<int>(t)});
  }
  std::vector<MovingRegion> regions;
  if (static_cast<int>(points.size()) < options.min_cluster_points) return regions;

  const int n = static_cast<int>(points.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const double radius2 = options.cluster_radius * options.cluster_radius;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double dx = points[i].p.x - points[j].p.x;
      const double dy = points[i].p.y - points[j].p.y;
      if (dx * dx + dy * dy > radius2) continue;
      if (std::abs(points[i].depth - points[j].depth) > options.cluster_depth_step) continue;
      const int a = Find(parent, i);
      const int b = Find(parent, j);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::vector<int>> clusters(n);
  for (int i = 0; i < n; ++i) clusters[Find(parent, i)].push_back(i);

  const cv::Rect whole(0, 0, depth.cols, depth.rows);
  const float step = static_cast<float>(options.region_depth_step);
  for (const std::vector<int>& cluster : clusters) {
    if (static_cast<int>(cluster.size()) < options.min_cluster_points) continue;
    std::vector<cv::Point> pixels;
    std::vector<double> depths;
    for (const int i : cluster) {
      pixels.emplace_back(static_cast<int>(points[i].p.x), static_cast<int>(points[i].p.y));
      depths.push_back(points[i].depth);
    }
    const double z = LowerMedian(std::move(depths));
    const int margin = GrowthMargin(z, focal_px, options);
    const cv::Rect spread = cv::boundingRect(pixels);
    const cv::Rect box = cv::Rect(spread.x - margin, spread.y - margin, spread.width + 2 * margin,
                                  spread.height + 2 * margin) &
                         whole;
    if (box.area() <= 0) continue;
    // Grow over depth-connected pixels from every point of the group, inside the box only, and
    // with the metric reach also within that reach of the group's depth: a surface the mover
    // touches (the floor under the feet, a wall leaned on) is not followed away from it.
    cv::Mat local = depth(box).clone();
    cv::Mat fill = cv::Mat::zeros(box.height + 2, box.width + 2, CV_8UC1);
    if (focal_px > 0.0 && options.region_reach > 0.0) {
      cv::Mat far;
      cv::compare(cv::abs(local - z), options.region_reach, far, cv::CMP_GT);
      fill(cv::Rect(1, 1, box.width, box.height)).setTo(kBlocked, far);
    }
    const int flags = 4 | cv::FLOODFILL_MASK_ONLY | (kGrown << 8);
    for (const cv::Point& pixel : pixels) {
      const cv::Point seed = pixel - box.tl();
      if (fill.at<uint8_t>(seed.y + 1, seed.x + 1) != 0) continue;
      cv::floodFill(local, fill, seed, cv::Scalar(), nullptr, cv::Scalar(step), cv::Scalar(step),
                    flags);
    }
    MovingRegion region;
    region.box = box;
    cv::compare(fill(cv::Rect(1, 1, box.width, box.height)), kGrown, region.mask, cv::CMP_EQ);
    if (!labelled.empty()) {
      cv::Mat outside;
      cv::bitwise_not(labelled(box), outside);
      cv::bitwise_and(region.mask, outside, region.mask);
    }
    region.points = static_cast<int>(cluster.size());
    for (const int i : cluster) region.members.push_back(points[i].track);
    regions.push_back(std::move(region));
  }
  return regions;
}

void PaintRegions(const std::vector<MovingRegion>& regions, cv::Mat& mask) {
  for (const MovingRegion& region : regions) {
    const cv::Rect box = region.box & cv::Rect(0, 0, mask.cols, mask.rows);
    if (box != region.box) continue;
    cv::Mat roi = mask(box);
    cv::bitwise_or(roi, region.mask, roi);
  }
}

}  // namespace drvslam
