// The matchers on a synthetic scene whose correspondences are known: random landmarks with
// random descriptors, observed from two poses with small descriptor noise.
#include "drvslam/match/orb_matcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "drvslam/map/map.h"

namespace drvslam {
namespace {

struct Scene {
  std::vector<Eigen::Vector3d> points;
  cv::Mat descriptors;  // one row per landmark
};

Scene MakeScene(int n, std::mt19937& rng) {
  Scene scene;
  std::uniform_real_distribution<double> xy(-1.5, 1.5), z(1.5, 4.0);
  std::uniform_int_distribution<int> byte(0, 255);
  scene.descriptors = cv::Mat(n, 32, CV_8U);
  for (int i = 0; i < n; ++i) {
    scene.points.emplace_back(xy(rng), xy(rng), z(rng));
    for (int b = 0; b < 32; ++b) scene.descriptors.at<uint8_t>(i, b) = byte(rng);
  }
  return scene;
}

// Observes the scene from T_cw: keypoints at the projections (level by index), descriptors with
// a few flipped bits, depth from the geometry. landmark_of[k] is the landmark of keypoint k.
std::shared_ptr<const FrameFeatures> Observe(const Scene& scene, const SE3& T_cw,
                                             const std::shared_ptr<const SensorGeometry>& geometry,
                                             std::mt19937& rng, std::vector<int>* landmark_of) {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv::Mat depth(geometry->camera.Height(), geometry->camera.Width(), CV_32F, cv::Scalar(0));
  std::uniform_int_distribution<int> bit(0, 255);
  landmark_of->clear();
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    const Eigen::Vector3d pc = T_cw * scene.points[i];
    const Eigen::Vector2d px = geometry->camera.Project(pc);
    if (pc.z() <= 0 || !geometry->InBounds(px.x(), px.y())) continue;
    cv::KeyPoint kp(static_cast<float>(px.x()), static_cast<float>(px.y()), 31.f, 45.f, 1.f,
                    static_cast<int>(i % 2));
    keypoints.push_back(kp);
    cv::Mat row = scene.descriptors.row(static_cast<int>(i)).clone();
    for (int f = 0; f < 5; ++f) {
      const int b = bit(rng);
      row.at<uint8_t>(0, b / 8) ^= static_cast<uint8_t>(1 << (b % 8));
    }
    descriptors.push_back(row);
    // InBounds admits a point on the last pixel's far edge, which rounds one past the image.
    const int row_index = std::min(static_cast<int>(std::lround(px.y())), depth.rows - 1);
    const int column = std::min(static_cast<int>(std::lround(px.x())), depth.cols - 1);
    depth.at<float>(row_index, column) = static_cast<float>(pc.z());
    landmark_of->push_back(static_cast<int>(i));
  }
  return std::make_shared<const FrameFeatures>(geometry, keypoints, descriptors, depth);
}

class OrbMatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    geometry_ = std::make_shared<const SensorGeometry>(CameraOptions{}, ScalePyramid(8, 1.2), 3.0);
    scene_ = MakeScene(600, rng_);
    // The first view at the origin, with a keyframe and map points at the true positions.
    std::vector<int> landmarks;
    auto features = Observe(scene_, SE3(), geometry_, rng_, &landmarks);
    first_ = std::make_unique<Frame>(0, 0.0, features);
    first_->SetPose(SE3());
    keyframe_ = std::make_shared<KeyFrame>(0, 0, 0.0, features, SE3(),
                                           std::vector<std::shared_ptr<MapPoint>>());
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
      auto point =
          std::make_shared<MapPoint>(static_cast<long>(k), scene_.points[landmarks[k]], keyframe_);
      point->AddObservation(keyframe_, static_cast<int>(k));
      keyframe_->AddMapPoint(point, k);
      point->ComputeDistinctiveDescriptor();
      point->UpdateNormalAndDepth(geometry_->pyramid);
      first_->map_points[k] = point;
      landmark_of_point_[point.get()] = landmarks[k];
    }
    // The second view moved 5 cm and rotated 2 degrees.
    second_pose_ = SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.035, Eigen::Vector3d(0, 1, 0))),
                       Eigen::Vector3d(0.05, -0.01, 0.02));
    second_features_ = Observe(scene_, second_pose_, geometry_, rng_, &second_landmarks_);
  }

  // (correct, wrong) matches in a frame observing the scene from the second pose.
  std::pair<int, int> Score(const Frame& frame) const {
    int correct = 0, wrong = 0;
    for (std::size_t k = 0; k < frame.Size(); ++k) {
      if (!frame.map_points[k]) continue;
      if (landmark_of_point_.at(frame.map_points[k].get()) == second_landmarks_[k]) {
        ++correct;
      } else {
        ++wrong;
      }
    }
    return {correct, wrong};
  }

  // `matches` (what the search reported) are all in `frame`: over 90 % of its keypoints matched to
  // their true landmark and none to another.
  void ExpectMostMatchesTrueAndNoneWrong(const Frame& frame, int matches) const {
    const auto [correct, wrong] = Score(frame);
    EXPECT_EQ(matches, correct + wrong);
    EXPECT_GT(correct, 0.9 * frame.Size());
    EXPECT_EQ(wrong, 0);
  }

  std::mt19937 rng_{7};
  std::shared_ptr<const SensorGeometry> geometry_;
  Scene scene_;
  std::unique_ptr<Frame> first_;
  std::shared_ptr<KeyFrame> keyframe_;
  std::map<const MapPoint*, int> landmark_of_point_;
  SE3 second_pose_;
  std::shared_ptr<const FrameFeatures> second_features_;
  std::vector<int> second_landmarks_;
};

TEST_F(OrbMatcherTest, ProjectionFromLastFrameFindsTheTrueCorrespondences) {
  Frame second(1, 0.033, second_features_);
  second.SetPose(second_pose_);
  const int matches = OrbMatcher().SearchByProjection(second, *first_, 7.0);
  ExpectMostMatchesTrueAndNoneWrong(second, matches);
}

TEST_F(OrbMatcherTest, ProjectionFailsGracefullyFromAWrongPose) {
  Frame second(1, 0.033, second_features_);
  // 40 cm off: windows of 7 px hold other keypoints at best, whose descriptors are far.
  second.SetPose(
      SE3(second_pose_.Quaternion(), second_pose_.Translation() + Eigen::Vector3d(0.4, 0.0, 0.0)));
  OrbMatcher().SearchByProjection(second, *first_, 7.0);
  const auto [correct, wrong] = Score(second);
  EXPECT_LT(correct, 0.1 * second.Size());
  EXPECT_EQ(wrong, 0);
}

TEST_F(OrbMatcherTest, LocalMapProjectionMatchesVisiblePoints) {
  Frame second(1, 0.033, second_features_);
  second.SetPose(second_pose_);
  const auto points = keyframe_->MapPoints();
  std::vector<std::shared_ptr<MapPoint>> local;
  std::vector<std::optional<Frame::Projection>> projections;
  for (const auto& point : points) {
    if (!point) continue;
    local.push_back(point);
    projections.push_back(second.ProjectIfVisible(*point, 0.5));
  }
  const int matches = OrbMatcher().SearchByProjection(second, local, projections, 3.0);
  const auto [correct, wrong] = Score(second);
  EXPECT_EQ(matches, correct + wrong);
  EXPECT_GT(correct, 0.85 * second.Size());
  EXPECT_LE(wrong, 0.01 * second.Size());
}

TEST_F(OrbMatcherTest, DescriptorMatchingAgainstKeyFrameNeedsNoPose) {
  Frame second(1, 0.033, second_features_);
  const int matches = OrbMatcher().SearchByDescriptors(*keyframe_, second, 0.7);
  ExpectMostMatchesTrueAndNoneWrong(second, matches);
}

TEST_F(OrbMatcherTest, FrustumTestRejectsPointsBehindAndOutside) {
  Frame turned(2, 0.066, second_features_);
  // Looking backwards: every landmark is behind the camera.
  turned.SetPose(SE3(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY())),
                     Eigen::Vector3d::Zero()));
  int visible = 0;
  for (const auto& point : keyframe_->MapPoints()) {
    if (point && turned.ProjectIfVisible(*point, 0.5)) ++visible;
  }
  EXPECT_EQ(visible, 0);
}

}  // namespace
}  // namespace drvslam
