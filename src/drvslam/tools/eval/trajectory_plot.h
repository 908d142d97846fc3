// A picture of an ATE evaluation for people: on the left a top view of the ground truth and the
// aligned estimate with the error of every matched pose drawn as a short segment, on the right
// the ATE error over time. Drawn with OpenCV so that no plotting library is needed.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/eval/ate.h"

namespace drvslam {

// The top view uses the two world axes along which the ground truth extends most, at equal
// scale. `ate` must come from ComputeAte(gt, est, ...). Returns a BGR image.
cv::Mat RenderTrajectoryPlot(const Trajectory& gt, const Trajectory& est, const AteResult& ate);

// Renders and writes a PNG (whatever the file's extension). Throws Error naming the path when it
// cannot be written.
void WriteTrajectoryPlot(const std::string& path, const Trajectory& gt, const Trajectory& est,
                         const AteResult& ate);

}  // namespace drvslam
