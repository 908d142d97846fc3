#include "drvslam/loop/place_hypotheses.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace drvslam {
namespace {

bool SamePlace(const SE3& a, const SE3& b, const PlaceChoiceOptions& options) {
  const SE3 difference = a * b.Inverse();
  const double angle = Eigen::AngleAxisd(difference.Rotation()).angle();
  // Camera centres, not translations: a rotation alone moves the translation of T_cw.
  const double distance = (a.Inverse().Translation() - b.Inverse().Translation()).norm();
  return distance < options.same_place_metres && angle < options.same_place_radians;
}

}  // namespace

PlaceChoice ChoosePlace(const std::vector<PlaceHypothesis>& hypotheses, int min_inliers,
                        const PlaceChoiceOptions& options) {
  PlaceChoice choice;
  // place_of[h]: the place of hypothesis h, named by its first hypothesis.
  std::vector<std::size_t> place_of(hypotheses.size());
  std::vector<std::size_t> places;
  for (std::size_t h = 0; h < hypotheses.size(); ++h) {
    place_of[h] = h;
    for (const std::size_t p : places) {
      if (SamePlace(hypotheses[h].T_cw, hypotheses[p].T_cw, options)) {
        place_of[h] = p;
        break;
      }
    }
    if (place_of[h] == h) places.push_back(h);
  }
  choice.places = static_cast<int>(places.size());

  // Support: keypoints that are an inlier of any hypothesis of the place (hypotheses of one
  // place against different keyframes explain different parts of the frame).
  std::vector<int> support(places.size(), 0);
  std::vector<int> best_hypothesis(places.size(), -1);
  for (std::size_t k = 0; k < places.size(); ++k) {
    std::vector<bool> explained;
    for (std::size_t h = 0; h < hypotheses.size(); ++h) {
      if (place_of[h] != places[k]) continue;
      const auto& matches = hypotheses[h].matches;
      if (explained.size() < matches.size()) explained.resize(matches.size(), false);
      for (std::size_t i = 0; i < matches.size(); ++i) {
        if (matches[i]) explained[i] = true;
      }
      const int b = best_hypothesis[k];
      if (b < 0 || hypotheses[h].inliers > hypotheses[static_cast<std::size_t>(b)].inliers) {
        best_hypothesis[k] = static_cast<int>(h);
      }
    }
    support[k] = static_cast<int>(std::count(explained.begin(), explained.end(), true));
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < places.size(); ++k) {
    if (support[k] > support[best]) best = k;
  }
  if (places.empty()) return choice;
  choice.best_support = support[best];
  for (std::size_t k = 0; k < places.size(); ++k) {
    if (k != best) choice.runner_up_support = std::max(choice.runner_up_support, support[k]);
  }
  if (choice.runner_up_support >= options.max_runner_up_ratio * choice.best_support) {
    choice.ambiguous = true;
    return choice;
  }
  const int chosen = best_hypothesis[best];
  if (hypotheses[static_cast<std::size_t>(chosen)].inliers >= min_inliers) choice.best = chosen;
  return choice;
}

}  // namespace drvslam
