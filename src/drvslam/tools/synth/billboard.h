// Billboards: actors cut out of real photographs (RGBA PNGs whose alpha marks the person), drawn
// as an upright quad turned towards the camera, so that a real detector sees a real person.
// Transparent texels (alpha < 128) are not drawn: no colour, no depth, no mask.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/tools/synth/scene.h"

namespace drvslam::synth {

// Every .png in `folder`, sorted by name, each cropped to the bounding box of its opaque
// pixels (CV_8UC4). Throws Error naming the folder when it is missing or holds no PNG, and
// naming the file when one cannot be read, has no alpha channel or is fully transparent.
std::vector<cv::Mat> LoadBillboards(const std::string& folder);

struct BillboardPlacement {
  Eigen::Vector3d base;        // bottom centre, on the floor (world)
  Eigen::Vector2d facing;      // horizontal unit direction the picture faces (towards the camera)
  Eigen::Vector2d sway{0, 0};  // horizontal offset of the top edge (metres): small motions
};

// Appends the double-sided quad, `width` x `height` metres, showing `texture`.
void AppendBillboard(int texture, double width, double height, const BillboardPlacement& placement,
                     int instance_id, TriangleList* out);

}  // namespace drvslam::synth
