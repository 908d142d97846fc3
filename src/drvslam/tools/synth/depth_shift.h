// Depth misregistration: a real RGB-D camera's depth image is registered to colour only as well
// as its calibration allows, often a pixel or two off. ShiftDepth moves the depth image (and the
// incidence image, which decides the sensor's grazing-angle holes) against colour and masks.
#pragma once

#include "drvslam/tools/synth/rasterizer.h"

namespace drvslam::synth {

// Depths whose spread is at most this share of the nearest one lie on one continuous surface
// (the sensor model's default depth-edge ratio).
inline constexpr double kDepthContinuity = 0.03;

// Moves depth by (dx, dy) pixels: depth at (x, y) becomes the depth at (x - dx, y - dy), 0 where
// that lies outside the image. Where the four depths around a sub-pixel source lie on one
// surface (kDepthContinuity) depth is interpolated bilinearly; elsewhere, and for incidence, the
// pixel at the shift rounded to whole pixels (halves away from zero) is taken, so a depth edge
// moves by the rounded shift and never blends foreground into background. Colour and instance ids
// are left as they are.
void ShiftDepth(double dx, double dy, RenderBuffers* buffers);

}  // namespace drvslam::synth
