#include "drvslam/loop/relocalization_options.h"

#include <cmath>
#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {

void RelocalizationOptions::Check() const {
  RequireOption(min_bow_matches >= 4, "Relocalization.minBowMatches", min_bow_matches,
                "must be at least 4 (PnP needs 4 points)");
  RequireOption(ransac_iterations >= 1, "Relocalization.ransacIterations", ransac_iterations,
                "must be at least 1");
  RequireOption(std::isfinite(ransac_reprojection_error) && ransac_reprojection_error > 0,
                "Relocalization.ransacReprojectionError", ransac_reprojection_error,
                "must be a positive number of pixels");
  RequireOption(min_pnp_inliers >= 4, "Relocalization.minPnpInliers", min_pnp_inliers,
                "must be at least 4");
  RequireOption(min_inliers >= min_pnp_inliers, "Relocalization.minInliers", min_inliers,
                "must be at least Relocalization.minPnpInliers");
}

RelocalizationOptions LoadRelocalizationOptions(const SettingsFile& file) {
  RelocalizationOptions o;
  o.enabled = file.GetBool("Relocalization.enabled", o.enabled);
  o.vocabulary = file.GetString("Relocalization.vocabulary", o.vocabulary);
  // A relative path names a file beside the settings file, wherever the run starts from.
  if (!o.vocabulary.empty() && std::filesystem::path(o.vocabulary).is_relative()) {
    o.vocabulary =
        (std::filesystem::path(file.Path()).parent_path() / o.vocabulary).lexically_normal();
  }
  o.min_bow_matches = file.GetInt("Relocalization.minBowMatches", o.min_bow_matches);
  o.ransac_iterations = file.GetInt("Relocalization.ransacIterations", o.ransac_iterations);
  o.ransac_reprojection_error =
      file.GetDouble("Relocalization.ransacReprojectionError", o.ransac_reprojection_error);
  o.min_pnp_inliers = file.GetInt("Relocalization.minPnpInliers", o.min_pnp_inliers);
  o.min_inliers = file.GetInt("Relocalization.minInliers", o.min_inliers);
  return CheckedOptions(file.Path(), o);
}

}  // namespace drvslam
