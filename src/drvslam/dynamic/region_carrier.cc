#include "drvslam/dynamic/region_carrier.h"

namespace drvslam {

std::vector<MovingRegion> CarryRegions(const std::vector<MovingRegion>& regions,
                                       const std::vector<FlowTrack>& tracks, const cv::Size& size,
                                       const ObjectMaskCarrier& carrier) {
  const cv::Rect whole(0, 0, size.width, size.height);
  // The carrier moves whole-image masks; source_id keeps each one's region.
  std::vector<Instance> instances;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const MovingRegion& region = regions[r];
    const cv::Rect box = region.box & whole;
    if (region.mask.size() != region.box.size() || box.empty()) continue;
    Instance instance;
    instance.mask = cv::Mat::zeros(size, CV_8UC1);
    region.mask(cv::Rect(box.tl() - region.box.tl(), box.size())).copyTo(instance.mask(box));
    instance.box = box;
    instance.source_id = static_cast<int>(r);
    instances.push_back(std::move(instance));
  }
  if (instances.empty()) return {};
  std::vector<MovingRegion> carried;
  for (const Instance& moved : carrier.Carry(instances, PointMotionsOf(tracks), size)) {
    MovingRegion region;
    region.box = moved.box;
    region.mask = moved.mask(moved.box).clone();
    region.points = regions[static_cast<std::size_t>(moved.source_id)].points;
    carried.push_back(std::move(region));
  }
  return carried;
}

std::vector<MovingRegion> WithoutCovered(std::vector<MovingRegion> carried,
                                         const std::vector<MovingRegion>& found,
                                         const cv::Size& size) {
  if (found.empty() || carried.empty()) return carried;
  cv::Mat covered = cv::Mat::zeros(size, CV_8UC1);
  PaintRegions(found, covered);
  const cv::Rect whole(0, 0, size.width, size.height);
  std::vector<MovingRegion> kept;
  for (MovingRegion& region : carried) {
    const cv::Rect box = region.box & whole;
    if (box.empty() || region.mask.size() != region.box.size()) continue;
    const cv::Mat mask = region.mask(cv::Rect(box.tl() - region.box.tl(), box.size()));
    cv::Mat overlap;
    cv::bitwise_and(mask, covered(box), overlap);
    if (2 * cv::countNonZero(overlap) < cv::countNonZero(mask)) kept.push_back(std::move(region));
  }
  return kept;
}

}  // namespace drvslam
