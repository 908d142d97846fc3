// Cost of the keyframe rule's reference count, once per tracked frame: ORB-SLAM2's count of the
// reference keyframe's well-observed points (WellObservedPoints, before Tracking.keyframeOcclusion)
// and that count with the points hidden behind something nearer, in one pass (CountReferencePoints,
// which replaces it when the option is on).
// A reference keyframe with state.range(0) points on a wall 3 m away, half the view covered by
// someone 1.5 m away.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "drvslam/map/frame_features.h"
#include "drvslam/map/map_point.h"
#include "drvslam/tracking/keyframe_occlusion.h"
#include "drvslam/tracking/observation_weight.h"

namespace drvslam {
namespace {

CameraOptions BenchCamera() {
  CameraOptions camera;
  camera.fx = camera.fy = 525.0;
  camera.cx = 319.5;
  camera.cy = 239.5;
  camera.width = 640;
  camera.height = 480;
  camera.bf = 40.0;
  return camera;
}

std::shared_ptr<KeyFrame> ReferenceWithPoints(int count) {
  const PinholeCamera camera(BenchCamera());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> column(0.0, 639.0), row(0.0, 479.0);
  std::vector<cv::KeyPoint> keypoints;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d pixel(column(random), row(random));
    keypoints.emplace_back(static_cast<float>(pixel.x()), static_cast<float>(pixel.y()), 31.f);
    points.push_back(camera.Backproject(pixel, 3.0));
  }
  const auto geometry = std::make_shared<SensorGeometry>(BenchCamera(), ScalePyramid(8, 1.2), 3.0);
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  auto features = std::make_shared<const FrameFeatures>(geometry, keypoints,
                                                        cv::Mat::zeros(count, 32, CV_8UC1), depth);
  auto keyframe =
      std::make_shared<KeyFrame>(0, 0, 0.0, features, SE3::Identity(),
                                 std::vector<std::shared_ptr<MapPoint>>(keypoints.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto point = std::make_shared<MapPoint>(static_cast<long>(i), points[i], keyframe);
    point->AddObservation(keyframe, static_cast<int>(i));
    keyframe->AddMapPoint(point, i);
  }
  return keyframe;
}

cv::Mat HalfCovered() {
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  depth(cv::Rect(0, 0, 320, 480)).setTo(1.5f);
  return depth;
}

void BM_WellObservedPoints(benchmark::State& state) {
  const auto keyframe = ReferenceWithPoints(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(WellObservedPoints(*keyframe, 2));
}
BENCHMARK(BM_WellObservedPoints)
    ->Arg(500)
    ->Arg(1000)
    ->ArgName("points")
    ->Unit(benchmark::kMicrosecond);

void BM_CountReferencePoints(benchmark::State& state) {
  const auto keyframe = ReferenceWithPoints(static_cast<int>(state.range(0)));
  const PinholeCamera camera(BenchCamera());
  const cv::Mat depth = HalfCovered();
  for (auto _ : state) {
    benchmark::DoNotOptimize(CountReferencePoints(*keyframe, 2, SE3::Identity(), camera, depth));
  }
}
BENCHMARK(BM_CountReferencePoints)
    ->Arg(500)
    ->Arg(1000)
    ->ArgName("points")
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
