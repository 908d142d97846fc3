#include "drvslam/dynamic/region_carrier.h"

#include <cmath>

#include "drvslam/core/lower_median.h"
#include "drvslam/core/pixel_index.h"

namespace drvslam {
namespace {

bool StartsOn(const MovingRegion& region, const FlowTrack& track) {
  cv::Point pixel;
  if (!PixelIndex(track.prev, &pixel) || !region.box.contains(pixel)) return false;
  return region.mask.at<uint8_t>(pixel - region.box.tl()) != 0;
}

}  // namespace

std::vector<MovingRegion> CarryRegions(const std::vector<MovingRegion>& regions,
                                       const std::vector<FlowTrack>& tracks, const cv::Size& size) {
  const cv::Rect whole(0, 0, size.width, size.height);
  std::vector<MovingRegion> carried;
  for (const MovingRegion& region : regions) {
    if (region.mask.size() != region.box.size()) continue;
    std::vector<double> dx;
    std::vector<double> dy;
    for (const FlowTrack& track : tracks) {
      if (!StartsOn(region, track)) continue;
      dx.push_back(track.cur.x - track.prev.x);
      dy.push_back(track.cur.y - track.prev.y);
    }
    if (static_cast<int>(dx.size()) < kMinCarryTracks) continue;
    const cv::Point shift(static_cast<int>(std::lround(LowerMedian(std::move(dx)))),
                          static_cast<int>(std::lround(LowerMedian(std::move(dy)))));
    const cv::Rect moved = cv::Rect(region.box.tl() + shift, region.box.size());
    const cv::Rect kept = moved & whole;
    if (kept.area() <= 0) continue;
    MovingRegion next;
    next.box = kept;
    next.mask = region.mask(cv::Rect(kept.tl() - moved.tl(), kept.size())).clone();
    next.points = region.points;
    carried.push_back(std::move(next));
  }
  return carried;
}

}  // namespace drvslam
