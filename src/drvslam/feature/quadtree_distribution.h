// Quad-tree keypoint distribution: keeps at most `target` corners of one pyramid level, spread
// evenly over the level. The region is split into quadrants, shallowest (largest) nodes first
// and, among equally deep ones, the most crowded first, until there are `target` non-empty
// nodes; each node then keeps its strongest corner. Crowded texture thus cannot take the whole
// budget, and empty (or masked) areas cost nothing, so the budget goes where corners are.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace drvslam {

// corners: level coordinates inside `region`, response = strength. On return holds the kept
// corners (all of them when there are no more than `target`; none when target <= 0). The
// result depends only on the input order and values: no ties are broken by chance.
void DistributeQuadtree(const cv::Rect& region, int target, std::vector<cv::KeyPoint>* corners);

}  // namespace drvslam
