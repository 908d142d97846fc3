#include "drvslam/tracking/depth_agreement.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

namespace drvslam {

DepthAgreement MeasureDepthAgreement(const Frame& frame, const cv::Mat& depth,
                                     const std::vector<std::shared_ptr<MapPoint>>& points,
                                     const DepthAgreementOptions& options) {
  DepthAgreement agreement;
  if (depth.empty() || depth.type() != CV_32FC1 || !frame.HasPose()) return agreement;
  std::vector<cv::Point3d> in_camera;
  for (const auto& point : points) {
    if (!point || point->IsBad()) continue;
    if (point->Visible() > 0 && point->FoundRatio() < options.min_found_ratio) continue;
    if (!frame.ProjectIfVisible(*point, options.min_view_cos)) continue;
    const Eigen::Vector3d p = frame.Pose() * point->Position();
    in_camera.emplace_back(p.x(), p.y(), p.z());
  }
  agreement.expected = static_cast<int>(in_camera.size());
  if (in_camera.empty()) return agreement;
  // The depth image is in the lens's pixels; the projection test above in undistorted ones.
  const PinholeCamera& camera = frame.Geometry().camera;
  const cv::Matx33d K(camera.Fx(), 0, camera.Cx(), 0, camera.Fy(), camera.Cy(), 0, 0, 1);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(in_camera, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                    camera.Options().HasDistortion() ? camera.DistortionCoeffs() : cv::Mat(),
                    pixels);
  for (std::size_t k = 0; k < in_camera.size(); ++k) {
    const int u = static_cast<int>(std::lround(pixels[k].x));
    const int v = static_cast<int>(std::lround(pixels[k].y));
    const double predicted = in_camera[k].z;
    const double tolerance =
        std::max(options.tolerance_metres, options.tolerance_ratio * predicted);
    // The 3x3 pixels around the projection: keypoints sit on edges, where one pixel off is the
    // background; any neighbour at the predicted depth agrees, and the point is missing only
    // when even the nearest is behind it.
    bool measured = false, agrees = false;
    double nearest = 0.0;
    for (int y = std::max(0, v - 1); y <= std::min(depth.rows - 1, v + 1); ++y) {
      for (int x = std::max(0, u - 1); x <= std::min(depth.cols - 1, u + 1); ++x) {
        const double d = depth.at<float>(y, x);
        if (!(d > 0.0)) continue;
        nearest = measured ? std::min(nearest, d) : d;
        measured = true;
        agrees |= std::abs(d - predicted) <= tolerance;
      }
    }
    if (!measured) {
      ++agreement.unmeasured;
    } else if (agrees) {
      ++agreement.agree;
    } else if (nearest > predicted + tolerance) {
      ++agreement.missing;
    } else {
      ++agreement.occluded;
    }
  }
  return agreement;
}

bool DepthAgrees(const DepthAgreement& agreement, const DepthAgreementOptions& options) {
  if (agreement.Measured() < options.min_measured) return true;
  return agreement.AgreeShare() >= options.min_agree_share &&
         agreement.MissingShare() <= options.max_missing_share;
}

}  // namespace drvslam
