#include "drvslam/tools/truth/dense_truth_json.h"

#include <optional>

namespace drvslam {

nlohmann::json DenseTruthScoresJson(const DenseTruthScores& s) {
  const auto or_null = [](const std::optional<double>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
  };
  nlohmann::json json;
  json["points"] = s.points;
  json["ghosts"] = s.ghosts;
  json["ghost_share"] = or_null(s.ghost_share);
  json["distance"] = {{"mean", or_null(s.mean_distance)},
                      {"median", or_null(s.median_distance)},
                      {"p95", or_null(s.p95_distance)},
                      {"static_mean", or_null(s.static_mean_distance)},
                      {"static_p95", or_null(s.static_p95_distance)}};
  json["key_object_points"] = s.key_object_points;
  json["background_points"] = s.background_points;
  json["key_object_density"] = or_null(s.key_object_density);
  json["background_density"] = or_null(s.background_density);
  return json;
}

}  // namespace drvslam
