// Carrying confirmed regions of unlabelled motion through frames whose own evidence is not
// believed (blurred, misfit or camera-failure frames: motion_trust.h) or fits too loosely to
// confirm a region at once. A camera pan among walking people blurs a second of frames; with no
// regions in them every mover's features went back into the map, and on the real Bonn crowd dev
// half tracking was then lost for the rest of the sequence in 3 of 5 realtime runs (geometry
// alone). The mover is still there, and the flow tracks still say where it went. Blur spoils the
// residual tests far more than the displacement, which needs no scene model. The regions move as
// the masks of detected objects do when segmentation lags (ObjectMaskCarrier): by a similarity
// fitted to the tracks that start on them, or their median displacement when the tracks
// disagree.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/dynamic/point_motions.h"
#include "drvslam/dynamic/unlabelled_motion.h"
#include "drvslam/semantic/object_mask_carrier.h"

namespace drvslam {

// Each region of the previous frame moved along the `tracks` (prev -> cur) by `carrier`, in an
// image of `size`; its box is the moved mask's tight box. Regions the carrier drops (too few
// tracks start on them, or they left the image) are left out. The carried regions keep their
// point counts and have no members (no track of this frame formed them).
std::vector<MovingRegion> CarryRegions(const std::vector<MovingRegion>& regions,
                                       const std::vector<FlowTrack>& tracks, const cv::Size& size,
                                       const ObjectMaskCarrier& carrier = ObjectMaskCarrier());

// The regions of `carried` less than half of which `found` (regions of the same image of `size`)
// already covers: a carried region that this frame's evidence found again is not kept twice.
std::vector<MovingRegion> WithoutCovered(std::vector<MovingRegion> carried,
                                         const std::vector<MovingRegion>& found,
                                         const cv::Size& size);

}  // namespace drvslam
