#include "drvslam/tools/vocab/place_recognition_eval.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/core/se3.h"
#include "drvslam/feature/orb_extractor.h"
#include "drvslam/io/tum_dataset.h"

namespace drvslam {
namespace {

// The score ratio given to a query no other entry shares a word with.
constexpr double kUnmatchedRatio = 10.0;
// A keyframe's ground-truth pose must be stamped this close to its image (s), the TUM tools'
// association window.
constexpr double kMaxPoseStampDifference = 0.02;
constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

}  // namespace

bool ViewChange::IsIdentity() const {
  return rotation_deg == 0.0 && scale == 1.0 && gain == 1.0 && offset == 0.0;
}

cv::Mat ApplyViewChange(const cv::Mat& gray, const ViewChange& change) {
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw Error("ApplyViewChange: expected a non-empty CV_8UC1 image");
  }
  if (!(change.scale > 0.0)) {
    throw Error("ApplyViewChange: scale " + std::to_string(change.scale) + " must be > 0");
  }
  cv::Mat warped = gray;
  if (change.rotation_deg != 0.0 || change.scale != 1.0) {
    const cv::Point2f centre(0.5f * (gray.cols - 1), 0.5f * (gray.rows - 1));
    const cv::Mat transform = cv::getRotationMatrix2D(centre, change.rotation_deg, change.scale);
    cv::warpAffine(gray, warped, transform, gray.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                   cv::Scalar(0));
  }
  cv::Mat result;
  warped.convertTo(result, CV_8U, change.gain, change.offset);
  return result;
}

void PlaceRecognitionSetOptions::Check() const {
  images.Check();
  orb.Check();
  if (features_per_image < 1) {
    throw Error("place recognition: features per image = " + std::to_string(features_per_image) +
                " must be >= 1");
  }
  if (database_step < 1) {
    throw Error("place recognition: database step = " + std::to_string(database_step) +
                " must be >= 1");
  }
  if (query_offset < 0) {
    throw Error("place recognition: query offset = " + std::to_string(query_offset) +
                " must be >= 0");
  }
  if (!(change.scale > 0.0)) {
    throw Error("place recognition: scale = " + std::to_string(change.scale) + " must be > 0");
  }
}

PlaceRecognitionSet BuildPlaceRecognitionSet(const std::vector<std::string>& inputs,
                                             const PlaceRecognitionSetOptions& options) {
  options.Check();
  const std::vector<TrainingImageSource> sources = ListTrainingImages(inputs, options.images);
  // Which listed image is the database entry j, and whose query each listed image is.
  std::vector<int> database_of(sources.size(), -1);
  std::vector<int> query_of(sources.size(), -1);
  int entries = 0;
  for (std::size_t i = 0; i < sources.size(); i += options.database_step) {
    database_of[i] = entries;
    const std::size_t q = i + options.query_offset;
    if (q < sources.size()) query_of[q] = entries;
    ++entries;
  }
  if (entries < 2) {
    throw Error("place recognition: " + std::to_string(entries) +
                " database image(s); need at least 2");
  }
  PlaceRecognitionSet set;
  set.database.resize(entries);
  set.database_names.resize(entries);
  OrbExtractor extractor(options.orb);
  std::vector<cv::KeyPoint> keypoints;
  ForEachTrainingImage(
      sources, options.images,
      [&](std::size_t index, const TrainingImageSource& source, const cv::Mat& gray) {
        if (database_of[index] >= 0) {
          cv::Mat descriptors;
          extractor.Extract(gray, cv::Mat(), options.features_per_image, &keypoints, &descriptors);
          set.database[database_of[index]] = descriptors;
          set.database_names[database_of[index]] = source.Name();
        }
        if (query_of[index] >= 0) {
          cv::Mat descriptors;
          extractor.Extract(ApplyViewChange(gray, options.change), cv::Mat(),
                            options.features_per_image, &keypoints, &descriptors);
          set.queries.push_back(descriptors);
          set.query_names.push_back(source.Name());
          set.true_matches.push_back({query_of[index]});
          set.candidates.emplace_back();
        }
      });
  if (set.queries.empty()) throw Error("place recognition: no query image");
  return set;
}

double PlaceRecognitionResult::MeanRank() const {
  if (ranks.empty()) return 0.0;
  double sum = 0.0;
  for (int rank : ranks) sum += rank;
  return sum / ranks.size();
}

double PlaceRecognitionResult::MedianRank() const {
  if (ranks.empty()) return 0.0;
  std::vector<int> sorted = ranks;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t middle = sorted.size() / 2;
  return sorted.size() % 2 == 1 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
}

double PlaceRecognitionResult::RecallAt(int n) const {
  if (ranks.empty()) return 0.0;
  const auto hits = std::count_if(ranks.begin(), ranks.end(), [n](int rank) { return rank <= n; });
  return static_cast<double>(hits) / ranks.size();
}

double PlaceRecognitionResult::MeanScoreRatio() const {
  if (true_scores.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < true_scores.size(); ++i) {
    sum += best_other_scores[i] > 0.0 ? true_scores[i] / best_other_scores[i] : kUnmatchedRatio;
  }
  return sum / true_scores.size();
}

PlaceRecognitionResult EvaluatePlaceRecognition(const BowVocabulary& vocabulary,
                                                const PlaceRecognitionSet& set) {
  const std::size_t queries = set.queries.size();
  // The summaries of a result without queries would be made-up numbers.
  if (queries == 0) throw Error("place recognition: no query to rank");
  if (set.true_matches.size() != queries || set.candidates.size() != queries) {
    throw Error("place recognition: " + std::to_string(queries) + " queries but " +
                std::to_string(set.true_matches.size()) + " true-match lists and " +
                std::to_string(set.candidates.size()) + " candidate lists");
  }
  const int database_size = static_cast<int>(set.database.size());
  const auto check_entry = [&](int entry, std::size_t query, const char* what) {
    if (entry < 0 || entry >= database_size) {
      throw Error("place recognition: " + std::string(what) + " " + std::to_string(entry) +
                  " of query " + std::to_string(query) + " out of range [0, " +
                  std::to_string(database_size) + ")");
    }
  };
  std::vector<BowVector> database(set.database.size());
  for (std::size_t i = 0; i < set.database.size(); ++i) {
    vocabulary.Transform(set.database[i], &database[i], nullptr, 0);
  }
  PlaceRecognitionResult result;
  result.database_size = database.size();
  BowVector query;
  std::vector<char> is_true(database.size(), 0);
  std::vector<int> all(database.size());
  for (int i = 0; i < database_size; ++i) all[i] = i;
  for (std::size_t q = 0; q < queries; ++q) {
    if (set.true_matches[q].empty()) {
      throw Error("place recognition: query " + std::to_string(q) + " has no true match");
    }
    for (int entry : set.true_matches[q]) check_entry(entry, q, "true match");
    for (int entry : set.candidates[q]) check_entry(entry, q, "candidate");
    vocabulary.Transform(set.queries[q], &query, nullptr, 0);
    double true_score = 0.0;
    for (int entry : set.true_matches[q]) {
      is_true[entry] = 1;
      true_score = std::max(true_score, BowVocabulary::Score(query, database[entry]));
    }
    int rank = 1;
    double best_other = 0.0;
    for (int entry : set.candidates[q].empty() ? all : set.candidates[q]) {
      if (is_true[entry]) continue;
      const double score = BowVocabulary::Score(query, database[entry]);
      if (score >= true_score) ++rank;
      best_other = std::max(best_other, score);
    }
    for (int entry : set.true_matches[q]) is_true[entry] = 0;
    result.ranks.push_back(rank);
    result.true_scores.push_back(true_score);
    result.best_other_scores.push_back(best_other);
  }
  return result;
}

void RevisitSetOptions::Check() const {
  orb.Check();
  if (features_per_image < 1) {
    throw Error("revisits: features per image = " + std::to_string(features_per_image) +
                " must be >= 1");
  }
  if (frame_step < 1) {
    throw Error("revisits: frame step = " + std::to_string(frame_step) + " must be >= 1");
  }
  if (!(min_gap_seconds >= 0.0)) {
    throw Error("revisits: minimum time gap = " + std::to_string(min_gap_seconds) +
                " must be >= 0");
  }
  if (!(max_distance > 0.0)) {
    throw Error("revisits: maximum distance = " + std::to_string(max_distance) + " must be > 0");
  }
  if (!(max_angle_deg > 0.0)) {
    throw Error("revisits: maximum angle = " + std::to_string(max_angle_deg) + " must be > 0");
  }
}

PlaceRecognitionSet BuildRevisitSet(const std::string& sequence_folder,
                                    const RevisitSetOptions& options) {
  options.Check();
  const TumDataset dataset(sequence_folder);
  if (!dataset.HasGroundTruth()) {
    throw Error(sequence_folder + ": no groundtruth.txt, so revisits are unknown");
  }
  const Trajectory& truth = dataset.GroundTruth();
  // Keyframes: every frame_step-th frame that has a ground-truth pose.
  std::vector<std::size_t> frames;
  std::vector<SE3> poses;
  std::vector<double> stamps;
  for (std::size_t i = 0; i < dataset.Size(); i += options.frame_step) {
    const double stamp = dataset.Timestamp(i);
    const auto after =
        std::lower_bound(truth.begin(), truth.end(), stamp,
                         [](const StampedPose& pose, double t) { return pose.timestamp < t; });
    const StampedPose* nearest = nullptr;
    if (after != truth.end()) nearest = &*after;
    if (after != truth.begin()) {
      const StampedPose* before = &*(after - 1);
      if (nearest == nullptr ||
          std::abs(before->timestamp - stamp) < std::abs(nearest->timestamp - stamp)) {
        nearest = before;
      }
    }
    if (nearest == nullptr || std::abs(nearest->timestamp - stamp) > kMaxPoseStampDifference) {
      continue;
    }
    frames.push_back(i);
    poses.push_back(nearest->T_wc);
    stamps.push_back(stamp);
  }
  PlaceRecognitionSet set;
  const double max_angle = options.max_angle_deg * kRadiansPerDegree;
  std::vector<std::vector<int>> true_matches(frames.size());
  std::vector<std::vector<int>> candidates(frames.size());
  for (std::size_t q = 0; q < frames.size(); ++q) {
    for (std::size_t k = 0; k < frames.size(); ++k) {
      if (std::abs(stamps[k] - stamps[q]) < options.min_gap_seconds || k == q) continue;
      candidates[q].push_back(static_cast<int>(k));
      const double distance = (poses[k].Translation() - poses[q].Translation()).norm();
      const double angle = RotationAngle(poses[q].Inverse() * poses[k]);
      if (distance <= options.max_distance && angle <= max_angle) {
        true_matches[q].push_back(static_cast<int>(k));
      }
    }
  }
  OrbExtractor extractor(options.orb);
  std::vector<cv::KeyPoint> keypoints;
  set.database.resize(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const RgbdFrame frame = dataset.Read(frames[k]);
    cv::Mat gray;
    cv::cvtColor(frame.bgr, gray, cv::COLOR_BGR2GRAY);
    extractor.Extract(gray, cv::Mat(), options.features_per_image, &keypoints, &set.database[k]);
    set.database_names.push_back(frame.rgb_path);
  }
  for (std::size_t q = 0; q < frames.size(); ++q) {
    if (true_matches[q].empty()) continue;
    set.queries.push_back(set.database[q]);
    set.query_names.push_back(set.database_names[q]);
    set.true_matches.push_back(std::move(true_matches[q]));
    set.candidates.push_back(std::move(candidates[q]));
  }
  if (set.queries.empty()) {
    throw Error(sequence_folder + ": no keyframe revisits the place of another (" +
                std::to_string(frames.size()) + " keyframes)");
  }
  return set;
}

}  // namespace drvslam
