// Carrying confirmed regions of unlabelled motion through frames whose own evidence is not
// believed (a blurred frame: motion_trust.h). A camera pan among walking people blurs a second
// of frames; with no regions in them every mover's features went back into the map, and on the
// real Bonn crowd dev half tracking was then lost for the rest of the sequence in 3 of 5
// realtime runs (geometry alone). The mover is still there, and the flow tracks still say where
// it went: each region is moved by the median displacement of the tracks that start on it.
// Blur spoils the residual tests far more than the displacement, which needs no scene model.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/dynamic/unlabelled_motion.h"

namespace drvslam {

// Tracks starting on a region that its displacement needs; fewer and the region is dropped
// (it left the view, or its texture did not survive).
constexpr int kMinCarryTracks = 3;

// Each region of the previous frame moved by the median displacement (prev -> cur) of the
// `tracks` whose previous point lies on it, and cropped to an image of `size`. Regions with
// fewer than kMinCarryTracks such tracks, or moved wholly out of the image, are dropped. The
// carried regions keep their point counts and have no members (no track of this frame formed
// them).
std::vector<MovingRegion> CarryRegions(const std::vector<MovingRegion>& regions,
                                       const std::vector<FlowTrack>& tracks, const cv::Size& size);

}  // namespace drvslam
