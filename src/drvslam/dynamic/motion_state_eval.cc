#include "drvslam/dynamic/motion_state_eval.h"

namespace drvslam {

void Confusion::Add(bool truth, bool judged) {
  if (truth && judged) ++true_positive;
  if (!truth && judged) ++false_positive;
  if (!truth && !judged) ++true_negative;
  if (truth && !judged) ++false_negative;
}

double Confusion::Precision() const {
  const std::size_t judged = true_positive + false_positive;
  return judged > 0 ? static_cast<double>(true_positive) / judged : 1.0;
}

double Confusion::Recall() const {
  const std::size_t moving = true_positive + false_negative;
  return moving > 0 ? static_cast<double>(true_positive) / moving : 1.0;
}

double Confusion::Accuracy() const {
  const std::size_t all = true_positive + false_positive + true_negative + false_negative;
  return all > 0 ? static_cast<double>(true_positive + true_negative) / all : 1.0;
}

void MotionStateEvaluator::Add(const DynamicFrameReport& report, const MotionTruth& truth) {
  for (std::size_t k = 0; k < report.objects.size() && k < report.instances.size(); ++k) {
    const ObjectEvidence& object = report.objects[k];
    if (!object.potentially_moving) continue;
    if (!object.model_ok) {
      ++scores_.no_model;
      continue;
    }
    const std::optional<bool> moving = truth(report.instances[k]);
    if (!moving) {
      ++scores_.unmatched;
      continue;
    }
    ++scores_.judged;
    scores_.delta_rule.Add(*moving, object.moving_delta_rule);
    scores_.share_rule.Add(*moving, object.moving_share_rule);
    scores_.reprojection_rule.Add(*moving, object.moving_reprojection_rule);
    scores_.combined_rule.Add(*moving, object.moving_combined_rule);
    scores_.shipped.Add(*moving, object.moving);
  }
}

nlohmann::json ConfusionJson(const Confusion& c) {
  return {{"tp", c.true_positive},   {"fp", c.false_positive},     {"tn", c.true_negative},
          {"fn", c.false_negative},  {"precision", c.Precision()}, {"recall", c.Recall()},
          {"accuracy", c.Accuracy()}};
}

nlohmann::json MotionStateScoresJson(const MotionStateScores& s) {
  return {{"judged", s.judged},
          {"unmatched", s.unmatched},
          {"no_model", s.no_model},
          {"delta_rule", ConfusionJson(s.delta_rule)},
          {"share_rule", ConfusionJson(s.share_rule)},
          {"reprojection_rule", ConfusionJson(s.reprojection_rule)},
          {"combined_rule", ConfusionJson(s.combined_rule)},
          {"shipped", ConfusionJson(s.shipped)}};
}

}  // namespace drvslam
