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

const OptionTable<RelocalizationOptions>& RelocalizationOptionTable() {
  static const OptionTable<RelocalizationOptions> table = [] {
    using R = RelocalizationOptions;
    OptionTable<R> t("Relocalization",
                     "how a lost tracker finds itself again (defaults: ORB-SLAM2)");
    t.Bool("enabled", &R::enabled,
           "0: no relocalization; a lost tracker retries against its last reference keyframe.")
        .Path("vocabulary", &R::vocabulary,
              "Bag-of-words vocabulary file, text or binary (empty: the build's default).")
        .Int("minBowMatches", &R::min_bow_matches, Bounds::AtLeast(4),
             "Bag-of-words matches a candidate keyframe needs before PnP is tried.")
        .Int("ransacIterations", &R::ransac_iterations, Bounds::AtLeast(1),
             "PnP RANSAC iterations (EPnP).")
        .Real("ransacReprojectionError", &R::ransac_reprojection_error,
              Bounds::Above(0).Note("pixels"), "PnP RANSAC inlier reprojection error.")
        .Int("minPnpInliers", &R::min_pnp_inliers, Bounds::AtLeast(4),
             "Inliers a PnP hypothesis needs before it is refined.")
        .Int("minInliers", &R::min_inliers, Bounds::AtLeast(4),
             "Inliers after pose optimization and guided search to accept the pose.")
        .Rule(
            "minInliers", [](const R& o) { return o.min_inliers >= o.min_pnp_inliers; },
            "must be at least Relocalization.minPnpInliers");
    return t;
  }();
  return table;
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
