// Measures how well a vocabulary recognizes places: for query images whose true database images
// are known (a rotated, scaled, relit view; a nearby frame; or, in a sequence with ground truth,
// an earlier keyframe taken from the same pose, as loop closing must find), the rank of the best
// true image when the candidates are sorted by BoW score. It decides between vocabularies (the
// build's default, one trained on the sequence, ORBvoc.txt) with numbers.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/tools/vocab/training_images.h"

namespace drvslam {

// A change of viewpoint and light: rotation about the image centre (degrees, counter-clockwise)
// and zoom (scale > 1 magnifies), then intensity' = gain * intensity + offset, saturated.
struct ViewChange {
  double rotation_deg = 0.0;
  double scale = 1.0;
  double gain = 1.0;
  double offset = 0.0;

  bool IsIdentity() const;
};

// gray: CV_8UC1; the result has its size; pixels from outside the image are black.
cv::Mat ApplyViewChange(const cv::Mat& gray, const ViewChange& change);

// Descriptors of database and query images and, per query, which database entries show its
// place and which it is ranked among.
struct PlaceRecognitionSet {
  std::vector<std::string> database_names;
  std::vector<cv::Mat> database;
  std::vector<std::string> query_names;
  std::vector<cv::Mat> queries;
  // Per query: the database entries of the same place (at least one).
  std::vector<std::vector<int>> true_matches;
  // Per query: the entries it is ranked among, true ones included; empty: the whole database.
  std::vector<std::vector<int>> candidates;
};

struct PlaceRecognitionSetOptions {
  TrainingImageOptions images;
  OrbExtractorOptions orb;
  int features_per_image = 1000;
  // The database is every database_step-th listed image; the query of database entry j is
  // listed image j * database_step + query_offset (when it exists) seen through `change`.
  int database_step = 1;
  int query_offset = 0;
  ViewChange change;

  void Check() const;
};

// Lists and reads `inputs` as vocabulary training does (ListTrainingImages) and extracts the
// descriptors of both sides. Throws drvslam::Error on bad options or inputs, or fewer than two
// database images.
PlaceRecognitionSet BuildPlaceRecognitionSet(const std::vector<std::string>& inputs,
                                             const PlaceRecognitionSetOptions& options);

// Revisits in an RGB-D sequence with ground truth (TUM layout): keyframes are every
// frame_step-th frame with a ground-truth pose (nearest stamp within 0.02 s); each keyframe is
// a query ranked among the keyframes at least min_gap_seconds away in time (loop closing skips
// recent ones), and its true matches are those whose camera centre lies within max_distance
// metres and whose rotation differs by at most max_angle_deg. Keyframes without any true match
// are no query.
struct RevisitSetOptions {
  OrbExtractorOptions orb;
  int features_per_image = 1000;
  int frame_step = 5;
  double min_gap_seconds = 5.0;
  double max_distance = 0.3;
  double max_angle_deg = 20.0;

  void Check() const;
};

// Throws drvslam::Error on bad options, a sequence that does not read (named by TumDataset),
// one without ground truth, or no keyframe with a revisit.
PlaceRecognitionSet BuildRevisitSet(const std::string& sequence_folder,
                                    const RevisitSetOptions& options);

struct PlaceRecognitionResult {
  // Per query: the 1-based rank of its best-scoring true entry among its candidates (false
  // entries scoring the same count as ahead of it), that score, and the best score of a false
  // candidate (0 when there is none).
  std::vector<int> ranks;
  std::vector<double> true_scores;
  std::vector<double> best_other_scores;
  std::size_t database_size = 0;

  double MeanRank() const;
  double MedianRank() const;
  // Share of queries whose true entry ranks <= n.
  double RecallAt(int n) const;
  // Mean of true score / best other score (> 1: the true entry stands out); queries whose best
  // other score is 0 count as 10.
  double MeanScoreRatio() const;
};

// Throws Error when the set has no query (so a result always has one) or inconsistent lists.
PlaceRecognitionResult EvaluatePlaceRecognition(const BowVocabulary& vocabulary,
                                                const PlaceRecognitionSet& set);

}  // namespace drvslam
