#include "drvslam/mapping/triangulation.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace drvslam {
namespace {

// One view of a candidate point.
struct View {
  const KeyFrame* keyframe;
  std::size_t index;
  SE3 T_cw;
  Eigen::Vector3d center;
  Eigen::Vector3d ray;  // normalized camera coordinates (x, y, 1)
  double u, v, right_u, depth;
  int level;
};

View MakeView(const KeyFrame& keyframe, std::size_t index, const SE3& T_cw,
              const Eigen::Vector3d& center) {
  const FrameFeatures& features = keyframe.Features();
  const cv::KeyPoint& kp = features.KeypointsUn()[index];
  const PinholeCamera& camera = keyframe.Geometry().camera;
  View view{&keyframe,
            index,
            T_cw,
            center,
            Eigen::Vector3d::Zero(),
            kp.pt.x,
            kp.pt.y,
            features.RightU(index),
            features.Depth(index),
            kp.octave};
  view.ray = Eigen::Vector3d((kp.pt.x - camera.Cx()) / camera.Fx(),
                             (kp.pt.y - camera.Cy()) / camera.Fy(), 1.0);
  return view;
}

// Cosine of the parallax a depth measurement offers: the angle the stereo baseline subtends
// at the measured depth. 2 (never the smallest) without depth.
double StereoParallaxCos(const View& view, double baseline) {
  if (view.right_u < 0 || view.depth <= 0) return 2.0;
  return std::cos(2.0 * std::atan2(baseline / 2.0, view.depth));
}

bool ReprojectsWell(const View& view, const Eigen::Vector3d& point_w,
                    const SensorGeometry& geometry, const TriangulationRules& rules) {
  const Eigen::Vector3d p = view.T_cw * point_w;
  if (p.z() <= 0) return false;
  const Eigen::Vector2d pixel = geometry.camera.Project(p);
  const double sigma2 = geometry.pyramid.sigma2[view.level];
  const double ex = pixel.x() - view.u;
  const double ey = pixel.y() - view.v;
  if (view.right_u < 0) return ex * ex + ey * ey <= rules.chi2_mono * sigma2;
  const double er = pixel.x() - geometry.Bf() / p.z() - view.right_u;
  return ex * ex + ey * ey + er * er <= rules.chi2_stereo * sigma2;
}

}  // namespace

std::optional<Eigen::Vector3d> TriangulateTwoViews(const SE3& T1w, const Eigen::Vector3d& ray1,
                                                   const SE3& T2w, const Eigen::Vector3d& ray2) {
  Eigen::Matrix<double, 3, 4> P1, P2;
  P1 << T1w.Rotation(), T1w.Translation();
  P2 << T2w.Rotation(), T2w.Translation();
  Eigen::Matrix4d A;
  A.row(0) = ray1.x() * P1.row(2) - P1.row(0);
  A.row(1) = ray1.y() * P1.row(2) - P1.row(1);
  A.row(2) = ray2.x() * P2.row(2) - P2.row(0);
  A.row(3) = ray2.y() * P2.row(2) - P2.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (!(std::abs(X(3)) > 1e-12)) return std::nullopt;
  const Eigen::Vector3d point = X.head<3>() / X(3);
  if (!point.allFinite()) return std::nullopt;
  return point;
}

std::vector<std::shared_ptr<MapPoint>> CreateNewMapPoints(const std::shared_ptr<KeyFrame>& keyframe,
                                                          Map& map, const OrbMatcher& matcher,
                                                          const TriangulationRules& rules,
                                                          const std::function<bool()>& stop) {
  std::vector<std::shared_ptr<MapPoint>> created;
  const SensorGeometry& geometry = keyframe->Geometry();
  const ScalePyramid& pyramid = geometry.pyramid;
  const double baseline = geometry.camera.Baseline();
  // Distances from the two cameras may differ by this much more than the levels suggest.
  const double ratio_factor = 1.5 * pyramid.scale_factor;
  const SE3 T1w = keyframe->Pose();
  const Eigen::Vector3d center1 = keyframe->CameraCenter();
  const Eigen::Matrix3d R1wt = T1w.Rotation().transpose();

  const auto neighbours = keyframe->BestCovisibles(static_cast<std::size_t>(rules.neighbours));
  for (std::size_t n = 0; n < neighbours.size(); ++n) {
    if (n > 0 && stop && stop()) break;
    const auto& neighbour = neighbours[n];
    if (neighbour->IsBad()) continue;
    const SE3 T2w = neighbour->Pose();
    const Eigen::Vector3d center2 = neighbour->CameraCenter();
    if ((center2 - center1).norm() < baseline) continue;
    const Eigen::Matrix3d R2wt = T2w.Rotation().transpose();

    for (const auto& [i1, i2] : matcher.SearchForTriangulation(*keyframe, *neighbour)) {
      const View view1 = MakeView(*keyframe, i1, T1w, center1);
      const View view2 = MakeView(*neighbour, i2, T2w, center2);
      const Eigen::Vector3d ray1 = R1wt * view1.ray;
      const Eigen::Vector3d ray2 = R2wt * view2.ray;
      const double rays_cos = ray1.dot(ray2) / (ray1.norm() * ray2.norm());
      const double stereo_cos1 = StereoParallaxCos(view1, baseline);
      const double stereo_cos2 = StereoParallaxCos(view2, baseline);
      const double stereo_cos = std::min({rays_cos + 1.0, stereo_cos1, stereo_cos2});
      const bool has_depth = view1.right_u >= 0 || view2.right_u >= 0;

      // Triangulate when the rays diverge more than any depth measurement would; otherwise
      // trust the depth with the larger parallax.
      std::optional<Eigen::Vector3d> point;
      if (rays_cos < stereo_cos && rays_cos > 0 &&
          (has_depth || rays_cos < rules.max_parallax_cos)) {
        point = TriangulateTwoViews(T1w, view1.ray, T2w, view2.ray);
      } else if (view1.right_u >= 0 && stereo_cos1 < stereo_cos2) {
        Eigen::Vector3d p;
        if (keyframe->UnprojectDepth(i1, &p)) point = p;
      } else if (view2.right_u >= 0 && stereo_cos2 < stereo_cos1) {
        Eigen::Vector3d p;
        if (neighbour->UnprojectDepth(i2, &p)) point = p;
      }
      if (!point) continue;
      if (!ReprojectsWell(view1, *point, geometry, rules) ||
          !ReprojectsWell(view2, *point, geometry, rules)) {
        continue;
      }
      const double distance1 = (*point - center1).norm();
      const double distance2 = (*point - center2).norm();
      if (distance1 <= 0 || distance2 <= 0) continue;
      const double distance_ratio = distance2 / distance1;
      const double level_ratio = pyramid.scale[view1.level] / pyramid.scale[view2.level];
      if (distance_ratio * ratio_factor < level_ratio ||
          distance_ratio > level_ratio * ratio_factor) {
        continue;
      }

      auto created_point = std::make_shared<MapPoint>(map.NextMapPointId(), *point, keyframe);
      created_point->AddObservation(keyframe, static_cast<int>(i1));
      created_point->AddObservation(neighbour, static_cast<int>(i2));
      keyframe->AddMapPoint(created_point, i1);
      neighbour->AddMapPoint(created_point, i2);
      created_point->ComputeDistinctiveDescriptor();
      created_point->UpdateNormalAndDepth(pyramid);
      map.AddMapPoint(created_point);
      created.push_back(std::move(created_point));
    }
  }
  return created;
}

}  // namespace drvslam
