#include "drvslam/dynamic/removal_policy.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {

double CoveredShare(const std::vector<Instance>& instances, const std::vector<bool>& selected,
                    const cv::Size& image) {
  if (selected.size() != instances.size()) {
    throw Error("CoveredShare: one flag per instance is needed");
  }
  if (image.area() <= 0) return 0.0;
  cv::Mat covered;
  int single = -1;
  int count = 0;
  for (std::size_t k = 0; k < instances.size(); ++k) {
    if (!selected[k] || instances[k].mask.empty()) continue;
    if (instances[k].mask.size() != image) {
      throw Error("CoveredShare: masks must have the image's size");
    }
    ++count;
    single = static_cast<int>(k);
  }
  if (count == 0) return 0.0;
  if (count == 1) {
    return static_cast<double>(cv::countNonZero(instances[single].mask)) / image.area();
  }
  covered = cv::Mat::zeros(image, CV_8UC1);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    if (!selected[k] || instances[k].mask.empty()) continue;
    const cv::Rect box = instances[k].box & cv::Rect(0, 0, image.width, image.height);
    if (box.area() <= 0) continue;
    cv::Mat roi = covered(box);
    cv::bitwise_or(roi, instances[k].mask(box), roi);
  }
  return static_cast<double>(cv::countNonZero(covered)) / image.area();
}

int BoostedFeatureTarget(int base, double previous_share, const DynamicOptions& options) {
  if (previous_share <= options.boost_share || previous_share <= 0.0) return base;
  const double factor = previous_share >= 1.0
                            ? options.max_feature_boost
                            : std::min(options.max_feature_boost, 1.0 / (1.0 - previous_share));
  return static_cast<int>(std::lround(base * factor));
}

RemovalPlan PlanRemoval(const std::vector<Instance>& instances,
                        const std::vector<bool>& potentially_moving,
                        const std::vector<bool>& moving, bool state_known, const cv::Size& image,
                        const DynamicOptions& options) {
  if (potentially_moving.size() != instances.size() || moving.size() != instances.size()) {
    throw Error("PlanRemoval: one flag per instance is needed");
  }
  RemovalPlan plan;
  plan.share = CoveredShare(instances, potentially_moving, image);
  plan.large_share = plan.share > options.large_share;
  plan.remove.assign(instances.size(), false);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    if (!potentially_moving[k]) continue;
    plan.remove[k] = !plan.large_share || !state_known || moving[k];
  }
  return plan;
}

cv::Mat RemovalMask(const std::vector<Instance>& instances, const RemovalPlan& plan,
                    const cv::Size& image, const DynamicOptions& options) {
  cv::Mat mask = cv::Mat::zeros(image, CV_8UC1);
  const cv::Rect whole(0, 0, image.width, image.height);
  const int grow = options.mask_dilation;
  const cv::Mat kernel =
      grow > 0 ? cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * grow + 1, 2 * grow + 1))
               : cv::Mat();
  for (std::size_t k = 0; k < instances.size(); ++k) {
    if (k >= plan.remove.size() || !plan.remove[k] || instances[k].mask.empty()) continue;
    const cv::Rect box = instances[k].box & whole;
    if (box.area() <= 0) continue;
    // Dilate only around the box, not over the whole image.
    const cv::Rect grown =
        cv::Rect(box.x - grow, box.y - grow, box.width + 2 * grow, box.height + 2 * grow) & whole;
    cv::Mat part = instances[k].mask(grown);
    if (grow > 0) {
      cv::Mat dilated;
      cv::dilate(part, dilated, kernel);
      part = dilated;
    }
    cv::Mat roi = mask(grown);
    cv::bitwise_or(roi, part, roi);
  }
  return mask;
}

}  // namespace drvslam
