#include "drvslam/tools/truth/motion_state_eval.h"

namespace drvslam {

namespace {

std::optional<double> Ratio(std::size_t part, std::size_t whole) {
  if (whole == 0) return std::nullopt;
  return static_cast<double>(part) / static_cast<double>(whole);
}

nlohmann::json OrNull(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

}  // namespace

void Confusion::Add(bool truth, bool judged) {
  if (truth && judged) ++true_positive;
  if (!truth && judged) ++false_positive;
  if (!truth && !judged) ++true_negative;
  if (truth && !judged) ++false_negative;
}

std::optional<double> Confusion::Precision() const {
  return Ratio(true_positive, true_positive + false_positive);
}

std::optional<double> Confusion::Recall() const {
  return Ratio(true_positive, true_positive + false_negative);
}

std::optional<double> Confusion::Accuracy() const {
  return Ratio(true_positive + true_negative,
               true_positive + false_positive + true_negative + false_negative);
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
  return {{"tp", c.true_positive},
          {"fp", c.false_positive},
          {"tn", c.true_negative},
          {"fn", c.false_negative},
          {"precision", OrNull(c.Precision())},
          {"recall", OrNull(c.Recall())},
          {"accuracy", OrNull(c.Accuracy())}};
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
