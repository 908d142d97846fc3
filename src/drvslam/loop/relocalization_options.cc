#include "drvslam/loop/relocalization_options.h"

namespace drvslam {

void RelocalizationOptions::Check() const { RelocalizationOptionTable().Check(*this); }

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
  return RelocalizationOptionTable().Load(file);
}

}  // namespace drvslam
