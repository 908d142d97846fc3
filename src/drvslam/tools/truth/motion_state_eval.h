// Scoring motion-state decisions against ground truth (the moving flags of a synthetic
// sequence's instances.txt): precision and recall of "moving" for the paper's delta rule, the
// epipolar track-share rule, the reprojection track-share rule and the rule that ships, over every
// potentially-moving object of every frame that had a scene model to judge with.
#pragma once

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "drvslam/dynamic/dynamic_front_end.h"

namespace drvslam {

struct Confusion {
  std::size_t true_positive = 0;  // moving, judged moving
  std::size_t false_positive = 0;
  std::size_t true_negative = 0;
  std::size_t false_negative = 0;

  void Add(bool truth, bool judged);
  // Undefined (nullopt) when there is nothing to score: precision when nothing was judged
  // moving, recall when nothing moved, accuracy when nothing was judged at all.
  std::optional<double> Precision() const;
  std::optional<double> Recall() const;
  std::optional<double> Accuracy() const;
};

struct MotionStateScores {
  Confusion delta_rule;         // the paper's rule
  Confusion share_rule;         // share of the object's tracks that break the epipolar geometry
  Confusion reprojection_rule;  // the object's tracks under the reprojection test alone
  Confusion combined_rule;      // Dynamic.motionRule combined
  Confusion shipped;            // Dynamic.motionRule
  std::size_t judged = 0;       // object-frames scored
  std::size_t unmatched = 0;    // potentially-moving objects without ground truth
  std::size_t no_model = 0;     // object-frames without a scene model (not scored)
};

// Whether the object an instance shows moves in its frame; nullopt when the instance matches no
// ground-truth object.
using MotionTruth = std::function<std::optional<bool>(const Instance&)>;

class MotionStateEvaluator {
 public:
  void Add(const DynamicFrameReport& report, const MotionTruth& truth);
  const MotionStateScores& Scores() const { return scores_; }

 private:
  MotionStateScores scores_;
};

// {"tp", "fp", "tn", "fn", "precision", "recall", "accuracy"}; an undefined ratio is null.
nlohmann::json ConfusionJson(const Confusion& confusion);
nlohmann::json MotionStateScoresJson(const MotionStateScores& scores);

}  // namespace drvslam
