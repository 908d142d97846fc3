#include "drvslam/dense/dense_options.h"

#include <cmath>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {

void DenseMapOptions::Check() const {
  RequireOption(std::isfinite(min_depth) && min_depth >= 0.0, "DenseMap.minDepth", min_depth,
                "must be >= 0");
  RequireOption(std::isfinite(max_depth) && max_depth > min_depth, "DenseMap.maxDepth", max_depth,
                "must be finite and above DenseMap.minDepth");
  RequireOption(std::isfinite(leaf_size) && leaf_size >= 0.001 && leaf_size <= 1.0,
                "DenseMap.leafSize", leaf_size, "must be in [0.001, 1] m");
  RequireOption(
      std::isfinite(object_leaf_size) && object_leaf_size >= 0.001 && object_leaf_size <= leaf_size,
      "DenseMap.objectLeafSize", object_leaf_size, "must be in [0.001 m, DenseMap.leafSize]");
  RequireOption(enhancement_frames >= 0 && enhancement_frames <= 64, "DenseMap.enhancementFrames",
                enhancement_frames, "must be in [0, 64]");
  RequireOption(mask_dilation >= 0 && mask_dilation <= 50, "DenseMap.maskDilation", mask_dilation,
                "must be in [0, 50] pixels");
  RequireOption(mask_growth >= 0 && mask_growth <= 200, "DenseMap.maskGrowth", mask_growth,
                "must be in [0, 200] pixels");
  RequireOption(std::isfinite(mask_growth_depth_band) && mask_growth_depth_band > 0.0,
                "DenseMap.maskGrowthDepthBand", mask_growth_depth_band, "must be > 0 m");
  RequireOption(
      std::isfinite(flying_pixel_step) && flying_pixel_step >= 0.0 && flying_pixel_step <= 1.0,
      "DenseMap.flyingPixelStep", flying_pixel_step, "must be in [0, 1]");
  RequireOption(min_views >= 1 && min_views <= 1000, "DenseMap.minViews", min_views,
                "must be in [1, 1000]");
  RequireOption(evidence_max >= 1 && evidence_max <= 1000, "DenseMap.evidenceMax", evidence_max,
                "must be in [1, 1000]");
  RequireOption(std::isfinite(carve_margin) && carve_margin > 0.0, "DenseMap.carveMargin",
                carve_margin, "must be > 0 m");
  RequireOption(std::isfinite(carve_margin_quadratic) && carve_margin_quadratic >= 0.0,
                "DenseMap.carveMarginQuadratic", carve_margin_quadratic, "must be >= 0 m per m^2");
  RequireOption(
      std::isfinite(octomap_resolution) &&
          (octomap_resolution == 0.0 || (octomap_resolution >= 0.005 && octomap_resolution <= 1.0)),
      "DenseMap.octomapResolution", octomap_resolution, "must be 0 or in [0.005, 1] m");
  RequireOption(min_neighbours >= 0 && min_neighbours <= 26, "DenseMap.minNeighbours",
                min_neighbours, "must be in [0, 26]");
  RequireOption(queue_capacity >= 1, "DenseMap.queueCapacity", queue_capacity,
                "must be at least 1");
  RequireOption(compact_every >= 1, "DenseMap.compactEvery", compact_every, "must be at least 1");
}

DenseMapOptions LoadDenseMapOptions(const SettingsFile& file) {
  DenseMapOptions o;
  o.enabled = file.GetBool("DenseMap.enabled", o.enabled);
  o.min_depth = file.GetDouble("DenseMap.minDepth", o.min_depth);
  o.max_depth = file.GetDouble("DenseMap.maxDepth", o.max_depth);
  o.leaf_size = file.GetDouble("DenseMap.leafSize", o.leaf_size);
  o.object_leaf_size = file.GetDouble("DenseMap.objectLeafSize", o.object_leaf_size);
  o.enhancement_frames = file.GetInt("DenseMap.enhancementFrames", o.enhancement_frames);
  o.remove_dynamic = file.GetBool("DenseMap.removeDynamic", o.remove_dynamic);
  o.remove_all_potentially_moving =
      file.GetBool("DenseMap.removeAllPotentiallyMoving", o.remove_all_potentially_moving);
  o.sticky_moving = file.GetBool("DenseMap.stickyMoving", o.sticky_moving);
  o.mask_dilation = file.GetInt("DenseMap.maskDilation", o.mask_dilation);
  o.mask_growth = file.GetInt("DenseMap.maskGrowth", o.mask_growth);
  o.mask_growth_depth_band =
      file.GetDouble("DenseMap.maskGrowthDepthBand", o.mask_growth_depth_band);
  o.flying_pixel_step = file.GetDouble("DenseMap.flyingPixelStep", o.flying_pixel_step);
  o.min_views = file.GetInt("DenseMap.minViews", o.min_views);
  o.evidence_max = file.GetInt("DenseMap.evidenceMax", o.evidence_max);
  o.carve = file.GetBool("DenseMap.carve", o.carve);
  o.neighbour_veto = file.GetBool("DenseMap.neighbourVeto", o.neighbour_veto);
  o.carve_margin = file.GetDouble("DenseMap.carveMargin", o.carve_margin);
  o.carve_margin_quadratic =
      file.GetDouble("DenseMap.carveMarginQuadratic", o.carve_margin_quadratic);
  o.octomap_resolution = file.GetDouble("DenseMap.octomapResolution", o.octomap_resolution);
  o.min_neighbours = file.GetInt("DenseMap.minNeighbours", o.min_neighbours);
  o.queue_capacity = file.GetInt("DenseMap.queueCapacity", o.queue_capacity);
  o.compact_every = file.GetInt("DenseMap.compactEvery", o.compact_every);
  return CheckedOptions(file.Path(), o);
}

}  // namespace drvslam
