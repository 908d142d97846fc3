#include "drvslam/loop/relocalizer.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/map/map_point.h"
#include "drvslam/match/bow_matcher.h"
#include "drvslam/match/keyframe_projection.h"
#include "drvslam/match/pose_observations.h"
#include "drvslam/optim/pose_optimizer.h"

namespace drvslam {
namespace {

// ORB-SLAM2's constants around the configurable thresholds: the BoW ratio test, the two guided
// searches (wide window and loose descriptor threshold first, then narrow and strict), the
// inliers under which a PnP pose is dropped after optimization, and over which the narrow
// second search is worth trying.
constexpr double kBowRatio = 0.75;
constexpr KeyFrameProjectionOptions kWideSearch{10.0, 100, true};
constexpr KeyFrameProjectionOptions kNarrowSearch{3.0, 64, true};
constexpr int kMinOptimizedInliers = 10;
constexpr int kMinInliersForNarrowSearch = 30;
constexpr double kRansacConfidence = 0.99;
// PnP poses tried per candidate: the best, then one from the matches it left out (a shifted
// copy of the place in repeated structure).
constexpr int kPosesPerCandidate = 2;
constexpr double kMinRivalShare = 0.5;

}  // namespace

int DirectIndexLevel(const BowVocabulary& vocabulary) {
  return std::max(0, vocabulary.Depth() - 4);
}

Relocalizer::Relocalizer(std::shared_ptr<const BowVocabulary> vocabulary,
                         KeyFrameDatabase& database, const RelocalizationOptions& options)
    : vocabulary_(std::move(vocabulary)), database_(database), options_(options) {
  options_.Check();
  if (!vocabulary_ || vocabulary_->Empty()) {
    throw Error("Relocalizer: the bag-of-words vocabulary is empty");
  }
  direct_index_level_ = DirectIndexLevel(*vocabulary_);
}

void Relocalizer::ComputeBow(Frame& frame) const {
  if (frame.has_bow) return;
  vocabulary_->Transform(frame.Features().Descriptors(), &frame.bow, &frame.bow_features,
                         direct_index_level_);
  frame.has_bow = true;
}

bool Relocalizer::Relocalize(Frame& frame) {
  ++attempts_;
  last_report_ = RelocalizationReport();
  ComputeBow(frame);
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  std::fill(frame.outlier.begin(), frame.outlier.end(), false);
  const auto candidates = database_.RelocalizationCandidates(frame.bow);
  last_report_.candidates = static_cast<int>(candidates.size());

  BowMatchOptions bow_options;
  bow_options.nn_ratio = kBowRatio;
  std::vector<std::shared_ptr<MapPoint>> matches;
  std::vector<PlaceHypothesis> hypotheses;
  // Every candidate, not the first good one: a wrong place is only seen next to the right one.
  for (const auto& candidate : candidates) {
    if (candidate->IsBad()) continue;
    const int bow_matches = SearchByBow(*candidate, frame, bow_options, &matches);
    if (bow_matches < options_.min_bow_matches) continue;
    ++last_report_.candidates_tried;
    TryCandidate(frame, candidate, matches, bow_matches, &hypotheses);
  }
  last_report_.hypotheses = static_cast<int>(hypotheses.size());
  last_report_.choice = ChoosePlace(hypotheses, options_.min_inliers);
  const PlaceChoice& choice = last_report_.choice;
  std::fill(frame.outlier.begin(), frame.outlier.end(), false);
  if (choice.ambiguous) {
    ++ambiguous_rejections_;
    spdlog::info(
        "frame {}: relocalization refused: {} places explain it almost equally well ({} and {} "
        "keypoints)",
        frame.Id(), choice.places, choice.best_support, choice.runner_up_support);
  }
  if (choice.best < 0) {
    std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
    return false;
  }
  const PlaceHypothesis& chosen = hypotheses[static_cast<std::size_t>(choice.best)];
  frame.SetPose(chosen.T_cw);
  frame.map_points = chosen.matches;
  frame.reference_keyframe = chosen.keyframe;
  last_report_.keyframe_id = chosen.keyframe->Id();
  last_report_.bow_matches = chosen.bow_matches;
  last_report_.pnp_inliers = chosen.pnp_inliers;
  last_report_.inliers = chosen.inliers;
  spdlog::debug(
      "relocalized frame {} against keyframe {}: {} candidates, {} places, {} BoW matches, {} PnP "
      "inliers, {} inliers",
      frame.Id(), chosen.keyframe->Id(), last_report_.candidates, choice.places, chosen.bow_matches,
      chosen.pnp_inliers, chosen.inliers);
  return true;
}

void Relocalizer::TryCandidate(Frame& frame, const std::shared_ptr<KeyFrame>& candidate,
                               const std::vector<std::shared_ptr<MapPoint>>& matches,
                               int bow_matches, std::vector<PlaceHypothesis>* hypotheses) const {
  const FrameFeatures& features = frame.Features();
  const PinholeCamera& camera = frame.Geometry().camera;
  const cv::Matx33d K(camera.Fx(), 0, camera.Cx(), 0, camera.Fy(), camera.Cy(), 0, 0, 1);
  // Matches an earlier PnP of this candidate took as inliers: in repeated structure the rest may
  // hold a second, shifted pose.
  std::vector<bool> used(matches.size(), false);
  int first_inliers = 0;
  for (int round = 0; round < kPosesPerCandidate; ++round) {
    std::vector<cv::Point3d> object_points;
    std::vector<cv::Point2d> image_points;
    std::vector<std::size_t> slots;
    for (std::size_t j = 0; j < matches.size(); ++j) {
      if (!matches[j] || used[j]) continue;
      const Eigen::Vector3d p = matches[j]->Position();
      object_points.emplace_back(p.x(), p.y(), p.z());
      const cv::KeyPoint& kp = features.KeypointsUn()[j];
      image_points.emplace_back(kp.pt.x, kp.pt.y);
      slots.push_back(j);
    }
    if (static_cast<int>(slots.size()) < options_.min_pnp_inliers) return;
    // A second pose from fewer matches than half the first's inliers could not rival it (the
    // choice asks for 80 %); RANSAC among outliers runs all its iterations, so it is skipped.
    if (round > 0 && static_cast<int>(slots.size()) < kMinRivalShare * first_inliers) return;
    cv::Mat rvec, tvec;
    std::vector<int> inliers;
    // Keypoints are undistorted already: no distortion coefficients.
    const bool solved = cv::solvePnPRansac(object_points, image_points, K, cv::noArray(), rvec,
                                           tvec, false, options_.ransac_iterations,
                                           static_cast<float>(options_.ransac_reprojection_error),
                                           kRansacConfidence, inliers, cv::SOLVEPNP_EPNP);
    if (!solved || static_cast<int>(inliers.size()) < options_.min_pnp_inliers) return;
    if (round == 0) first_inliers = static_cast<int>(inliers.size());
    std::vector<std::size_t> inlier_slots;
    for (const int k : inliers) {
      inlier_slots.push_back(slots[static_cast<std::size_t>(k)]);
      used[slots[static_cast<std::size_t>(k)]] = true;
    }
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    Eigen::Matrix3d rotation;
    cv::cv2eigen(cv::Mat(R), rotation);
    const Eigen::Vector3d translation(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
    if (!rotation.allFinite() || !translation.allFinite()) continue;
    frame.SetPose(SE3(rotation, translation));
    int good = 0;
    if (!RefineHypothesis(frame, *candidate, matches, inlier_slots, &good)) continue;
    PlaceHypothesis hypothesis;
    hypothesis.T_cw = frame.Pose();
    hypothesis.keyframe = candidate;
    hypothesis.matches = frame.map_points;
    hypothesis.inliers = good;
    hypothesis.bow_matches = bow_matches;
    hypothesis.pnp_inliers = static_cast<int>(inliers.size());
    hypotheses->push_back(std::move(hypothesis));
  }
}

bool Relocalizer::RefineHypothesis(Frame& frame, const KeyFrame& candidate,
                                   const std::vector<std::shared_ptr<MapPoint>>& matches,
                                   const std::vector<std::size_t>& inlier_slots,
                                   int* inliers) const {
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  for (const std::size_t slot : inlier_slots) frame.map_points[slot] = matches[slot];
  int good = OptimizeFramePose(frame);
  if (good < kMinOptimizedInliers) return false;

  // Few inliers: search the rest of the candidate's points around their projections.
  if (good < options_.min_inliers) {
    const int added = SearchKeyFrameByProjection(frame, candidate, kWideSearch);
    if (good + added >= options_.min_inliers) {
      good = OptimizeFramePose(frame);
      // Close to the threshold: a narrower, stricter search from the better pose.
      if (good >= kMinInliersForNarrowSearch && good < options_.min_inliers) {
        const int more = SearchKeyFrameByProjection(frame, candidate, kNarrowSearch);
        if (good + more >= options_.min_inliers) good = OptimizeFramePose(frame);
      }
    }
  }
  *inliers = good;
  return good >= kMinOptimizedInliers;
}

int Relocalizer::OptimizeFramePose(Frame& frame) const {
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> slots;
  const FrameFeatures& features = frame.Features();
  const ScalePyramid& pyramid = frame.Geometry().pyramid;
  GatherPoseObservations(features, pyramid, frame.map_points, &observations, &slots);
  if (observations.size() < 3) return 0;
  const PoseOptimizationResult result =
      OptimizePose(frame.Geometry().camera.Options(), frame.Pose(), observations);
  frame.SetPose(result.T_cw);
  int inliers = 0;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    frame.outlier[slots[k]] = false;
    if (result.outlier[k]) {
      frame.map_points[slots[k]].reset();
    } else {
      ++inliers;
    }
  }
  return inliers;
}

}  // namespace drvslam
