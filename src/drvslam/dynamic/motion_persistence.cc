#include "drvslam/dynamic/motion_persistence.h"

#include <algorithm>

#include "drvslam/core/error.h"

namespace drvslam {

std::vector<int> MotionPersistence::Update(const std::vector<MovingRegion>& regions,
                                           const std::vector<FlowTrack>& tracks,
                                           const cv::Size& image) {
  const bool have_previous = !streaks_.empty() && streaks_.size() == image;
  std::vector<int> streaks;
  streaks.reserve(regions.size());
  for (const MovingRegion& region : regions) {
    std::vector<int> before;
    for (const int member : region.members) {
      if (member < 0 || member >= static_cast<int>(tracks.size())) {
        throw Error("MotionPersistence: a region names a track that does not exist");
      }
      if (!have_previous) continue;
      const cv::Point2f& p = tracks[member].prev;
      const int x = static_cast<int>(p.x);
      const int y = static_cast<int>(p.y);
      const bool inside = x >= 0 && y >= 0 && x < image.width && y < image.height;
      before.push_back(inside ? streaks_.at<uint8_t>(y, x) : 0);
    }
    // The streak that at least a quarter of the points carry: a moving person's region grows
    // over different limbs from frame to frame, so not every point came from last frame's region.
    int previous = 0;
    if (!before.empty()) {
      const auto quartile = before.begin() + (3 * before.size()) / 4;
      std::nth_element(before.begin(), quartile, before.end());
      previous = *quartile;
    }
    streaks.push_back(std::min(previous + 1, 255));
  }
  Remember(regions, streaks, image);
  return streaks;
}

void MotionPersistence::Add(const std::vector<MovingRegion>& carried, const cv::Size& image,
                            int streak) {
  Remember(carried, std::vector<int>(carried.size(), std::clamp(streak, 1, 255)), image, true);
}

void MotionPersistence::Remember(const std::vector<MovingRegion>& regions,
                                 const std::vector<int>& streaks, const cv::Size& image,
                                 bool keep_previous) {
  cv::Mat next = streaks_;  // shares the pixels: painted in place
  if (!keep_previous || next.size() != image) next = cv::Mat::zeros(image, CV_8UC1);
  const cv::Rect whole(0, 0, image.width, image.height);
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const MovingRegion& region = regions[r];
    if ((region.box & whole) != region.box || region.mask.size() != region.box.size()) continue;
    cv::Mat roi = next(region.box);
    cv::Mat value(region.box.size(), CV_8UC1, cv::Scalar(streaks[r]));
    cv::Mat masked = cv::Mat::zeros(region.box.size(), CV_8UC1);
    value.copyTo(masked, region.mask);
    cv::max(roi, masked, roi);
  }
  streaks_ = next;
}

void MotionPersistence::Forget() { streaks_.release(); }

}  // namespace drvslam
