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

const OptionTable<DenseMapOptions>& DenseMapOptionTable() {
  static const OptionTable<DenseMapOptions> table = [] {
    using D = DenseMapOptions;
    OptionTable<D> t("DenseMap",
                     "the dense mapping thread: trusted depth, left-out pixels, voxel evidence, "
                     "key-object enhancement");
    t.Bool("enabled", &D::enabled, "Build the dense map (dense_map.ply, .pcd, .bt).")
        .Real("minDepth", &D::min_depth, Bounds::AtLeast(0).Note("metres"),
              "Depth nearer than this is left out.")
        .Real("maxDepth", &D::max_depth, Bounds::Any().Note("metres"),
              "Depth farther than this is left out.")
        .Real("leafSize", &D::leaf_size, Bounds::In(0.001, 1).Note("metres"),
              "Global map: one point per voxel of this edge.")
        .Real("objectLeafSize", &D::object_leaf_size, Bounds::AtLeast(0.001).Note("metres"),
              "Static key objects (books, laptops, ...): one point per voxel of this edge.")
        .Int("enhancementFrames", &D::enhancement_frames, Bounds::In(0, 64),
             "Frames nearest a keyframe whose key-object pixels are added too.")
        .Bool("removeDynamic", &D::remove_dynamic,
              "Leave out the pixels of objects judged moving (0 integrates everything).")
        .Bool("removeAllPotentiallyMoving", &D::remove_all_potentially_moving,
              "Leave out every potentially-moving object, moving or not.")
        .Bool("stickyMoving", &D::sticky_moving,
              "An object judged moving once stays out, its earlier still points too.")
        .Int("maskDilation", &D::mask_dilation, Bounds::In(0, 50).Note("pixels"),
             "Left-out masks grow by this much last (depth at borders belongs to either side).")
        .Int("maskGrowth", &D::mask_growth, Bounds::In(0, 200).Note("pixels"),
             "Left-out masks first grow at most this far along the object's own depth (0 = no "
             "growth).")
        .Real("maskGrowthDepthBand", &D::mask_growth_depth_band, Bounds::Above(0).Note("metres"),
              "Growth takes pixels within this of the object's median depth.")
        .Real("flyingPixelStep", &D::flying_pixel_step, Bounds::In(0, 1).Note("0 keeps them"),
              "A depth step to a 4-neighbour above this share of the depth drops the pixel.")
        .Int("minViews", &D::min_views, Bounds::In(1, 1000),
             "Keyframes that must see a point in a voxel before it is exported.")
        .Int("evidenceMax", &D::evidence_max, Bounds::In(1, 1000),
             "Voxel evidence is clamped to +-this, so a departed object is carved in bounded "
             "views.")
        .Bool("carve", &D::carve, "Keyframes seeing clearly behind a voxel take evidence away.")
        .Bool("neighbourVeto", &D::neighbour_veto,
              "Drop keyframe points a neighbouring frame sees inside a left-out object's mask.")
        .Real("carveMargin", &D::carve_margin, Bounds::Above(0).Note("metres"),
              "Behind by more than carveMargin + carveMarginQuadratic * depth^2 is clearly behind.")
        .Real("carveMarginQuadratic", &D::carve_margin_quadratic,
              Bounds::AtLeast(0).Note("metres per square metre"),
              "The depth-squared part of the carving margin.")
        .Real("octomapResolution", &D::octomap_resolution, Bounds::In(0, 1).Note("metres"),
              "Leaf of dense_map.bt, the OctoMap of occupied and free space (0 writes none).")
        .Int("minNeighbours", &D::min_neighbours, Bounds::In(0, 26),
             "Exported points need this many occupied neighbouring voxels (0 keeps all).")
        .Int("queueCapacity", &D::queue_capacity, Bounds::AtLeast(1),
             "Keyframes waiting for the dense thread before tracking blocks.")
        .Int("compactEvery", &D::compact_every, Bounds::AtLeast(1),
             "Re-key the stored map with current keyframe poses after this many keyframes.")
        .Rule(
            "maxDepth", [](const D& o) { return o.max_depth > o.min_depth; },
            "must be above DenseMap.minDepth")
        .Rule(
            "objectLeafSize", [](const D& o) { return o.object_leaf_size <= o.leaf_size; },
            "must not exceed DenseMap.leafSize")
        .Rule(
            "octomapResolution",
            [](const D& o) { return o.octomap_resolution == 0.0 || o.octomap_resolution >= 0.005; },
            "must be 0 or at least 0.005 m");
    return t;
  }();
  return table;
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
