// Jitter: how much a trajectory's camera centre shakes from frame to frame, the RMS of the second
// difference of consecutive centres. Motion-capture ground truth of a hand-held camera at 30 Hz
// has well under a millimetre; a pose a controller can difference into a velocity needs about
// that too.
#pragma once

#include <optional>

#include "drvslam/io/trajectory_io.h"

namespace drvslam {

// RMS over consecutive frame triples whose two intervals are each at most 1.5 times the
// trajectory's median interval (a lost or skipped frame between them would be a jump, not
// jitter), in metres; nullopt with fewer than 3 such triples.
std::optional<double> CentreJitter(const Trajectory& trajectory);

}  // namespace drvslam
