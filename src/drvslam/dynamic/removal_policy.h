// Removal policy: step 4 of the paper's dynamic-object handling, which keeps enough features
// when people fill much of the view. Before extraction, a frame whose predecessor was largely
// covered by potentially-moving objects asks the extractor for more features. Before tracking,
// when such objects cover a small share of the image every feature on them is dropped (cheap
// and safe: there is plenty of background); when they cover a large share, only the features
// on objects judged moving are dropped, so a person standing still in front of the camera still
// helps tracking.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// Share of the image's pixels inside at least one of the instances with selected[k] set.
double CoveredShare(const std::vector<Instance>& instances, const std::vector<bool>& selected,
                    const cv::Size& image);

// The extractor's target for a frame whose predecessor had `previous_share` covered:
// base * min(max_feature_boost, 1 / (1 - share)) above boost_share, else base.
int BoostedFeatureTarget(int base, double previous_share, const DynamicOptions& options);

struct RemovalPlan {
  double share = 0.0;        // image share of potentially-moving objects
  bool large_share = false;  // share > Dynamic.largeShare
  std::vector<bool> remove;  // per instance: drop its features
};

// potentially_moving / moving: per instance. `state_known`: whether motion states could be
// judged this frame (a scene model existed); when not, a large share still drops every
// potentially-moving object, as nothing says which of them stand still.
RemovalPlan PlanRemoval(const std::vector<Instance>& instances,
                        const std::vector<bool>& potentially_moving,
                        const std::vector<bool>& moving, bool state_known, const cv::Size& image,
                        const DynamicOptions& options);

// The union of the removed instances' masks, dilated by Dynamic.maskDilation (CV_8UC1, 255 =
// drop features there).
cv::Mat RemovalMask(const std::vector<Instance>& instances, const RemovalPlan& plan,
                    const cv::Size& image, const DynamicOptions& options);

}  // namespace drvslam
