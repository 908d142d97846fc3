#include "drvslam/dense/dense_options.h"

namespace drvslam {

void DenseMapOptions::Check() const { DenseMapOptionTable().Check(*this); }

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
        .Int("depthSmoothing", &D::depth_smoothing, Bounds::In(0, 10).Note("pixels"),
             "Background depth is averaged over this radius along its own surface before "
             "back-projection, and normals (which weight each view by its cosine) are taken "
             "over it (0 = raw depth).")
        .Int("minViews", &D::min_views, Bounds::In(1, 1000),
             "Keyframes that must see a point in a voxel before it is exported.")
        .Real("minViewSpan", &D::min_view_span, Bounds::In(0, 60).Note("seconds"),
              "A voxel's views must span this long, first to latest, before it is exported (0 = "
              "any): a person the detector misses for a moment plants nothing.")
        .Int("evidenceMax", &D::evidence_max, Bounds::In(1, 127),
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
        .Int("liveQueueCapacity", &D::live_queue_capacity, Bounds::AtLeast(1),
             "--realtime: keyframes waiting for the dense thread before new ones are dropped.")
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
  return DenseMapOptionTable().Load(file);
}

}  // namespace drvslam
