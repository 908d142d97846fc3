#include "drvslam/feature/fast_grid_detector.h"

#include <algorithm>
#include <cstdint>
#include <opencv2/features2d.hpp>

namespace drvslam {
namespace {

// FAST looks 3 pixels around each candidate and never reports corners within 3 pixels of the
// image it is given; searching `rect` grown by this margin reports corners inside `rect` only.
constexpr int kFastRadius = 3;

// Runs FAST over `rect` of `level` and appends the corners that the mask keeps, in level
// coordinates. Returns how many were appended.
int DetectInRect(const cv::Mat& level, const cv::Rect& rect, int threshold,
                 const LevelSkipMask& mask, std::vector<cv::KeyPoint>* corners,
                 std::vector<cv::KeyPoint>* scratch) {
  const cv::Rect search(rect.x - kFastRadius, rect.y - kFastRadius, rect.width + 2 * kFastRadius,
                        rect.height + 2 * kFastRadius);
  scratch->clear();
  cv::FAST(level(search), *scratch, threshold, /*nonmaxSuppression=*/true);
  const size_t before = corners->size();
  for (cv::KeyPoint& kp : *scratch) {
    kp.pt.x += search.x;
    kp.pt.y += search.y;
    if (!mask.Skips(kp.pt.x, kp.pt.y)) corners->push_back(kp);
  }
  return static_cast<int>(corners->size() - before);
}

}  // namespace

cv::Rect DetectionRegion(const cv::Size& level_size, int border) {
  return cv::Rect(border, border, std::max(0, level_size.width - 2 * border),
                  std::max(0, level_size.height - 2 * border));
}

void DetectFastGrid(const cv::Mat& level, const FastGridParams& params, const LevelSkipMask& mask,
                    std::vector<cv::KeyPoint>* corners, std::vector<cv::KeyPoint>* scratch) {
  corners->clear();
  const cv::Rect region = DetectionRegion(level.size(), params.border);
  if (region.empty() || params.border < kFastRadius) return;

  DetectInRect(level, region, params.ini_threshold, mask, corners, scratch);

  const int cells_x = std::max(1, cvRound(static_cast<double>(region.width) / params.cell_size));
  const int cells_y = std::max(1, cvRound(static_cast<double>(region.height) / params.cell_size));
  auto cell_edge = [](int origin, int length, int cells, int i) {
    return origin + static_cast<int>(static_cast<int64_t>(length) * i / cells);
  };
  // The cell holding offset d is the last i with cell_edge(i) <= d, i.e.
  // floor((cells * (d + 1) - 1) / length): the exact inverse of cell_edge's integer arithmetic.
  auto cell_of = [](int offset, int length, int cells) {
    return static_cast<int>((static_cast<int64_t>(cells) * (offset + 1) - 1) / length);
  };
  std::vector<int> counts(static_cast<size_t>(cells_x) * cells_y, 0);
  for (const cv::KeyPoint& kp : *corners) {
    const int cx = cell_of(cvRound(kp.pt.x) - region.x, region.width, cells_x);
    const int cy = cell_of(cvRound(kp.pt.y) - region.y, region.height, cells_y);
    ++counts[static_cast<size_t>(cy) * cells_x + cx];
  }
  for (int cy = 0; cy < cells_y; ++cy) {
    const int y0 = cell_edge(region.y, region.height, cells_y, cy);
    const int y1 = cell_edge(region.y, region.height, cells_y, cy + 1);
    for (int cx = 0; cx < cells_x; ++cx) {
      if (counts[static_cast<size_t>(cy) * cells_x + cx] > 0) continue;
      const int x0 = cell_edge(region.x, region.width, cells_x, cx);
      const int x1 = cell_edge(region.x, region.width, cells_x, cx + 1);
      const cv::Rect cell(x0, y0, x1 - x0, y1 - y0);
      if (cell.empty() || mask.Covers(cell)) continue;
      DetectInRect(level, cell, params.min_threshold, mask, corners, scratch);
    }
  }
}

}  // namespace drvslam
