#include "drvslam/match/pose_observations.h"

namespace drvslam {

void GatherPoseObservations(const FrameFeatures& features, const ScalePyramid& pyramid,
                            const std::vector<std::shared_ptr<MapPoint>>& points,
                            std::vector<PoseObservation>* observations,
                            std::vector<std::size_t>* slots) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& point = points[i];
    if (!point) continue;
    const cv::KeyPoint& kp = features.KeypointsUn()[i];
    PoseObservation observation;
    observation.point_w = point->Position();
    observation.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
    observation.right_u = features.RightU(i);
    observation.inv_sigma2 = pyramid.inv_sigma2[kp.octave];
    observations->push_back(observation);
    slots->push_back(i);
  }
}

}  // namespace drvslam
