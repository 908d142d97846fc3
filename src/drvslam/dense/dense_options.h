// DenseMapOptions: the DenseMap.* settings of the dense mapping thread (docs/architecture.md):
// which depth is trusted, which pixels are left out, the coarse leaf of the global map and the fine
// leaf and frame count of the targeted enhancement of static key objects.
#pragma once

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct DenseMapOptions {
  bool enabled = true;
  // Depth outside [min_depth, max_depth] (metres) is left out: Kinect-class sensors are noisy
  // beyond a few metres and invalid very close.
  double min_depth = 0.2;
  double max_depth = 4.0;
  // Global downsampling: one point per world voxel of this edge (metres).
  double leaf_size = 0.03;
  // Static key objects (books, laptops, keyboards, ...): one point per voxel of this edge.
  double object_leaf_size = 0.005;
  // Ordinary frames nearest in time to a keyframe whose key-object pixels are added too: half
  // of them (rounded down) before the keyframe, the rest after it, so a keyframe is integrated
  // once that many later frames have arrived (or at shutdown).
  int enhancement_frames = 4;
  // Leave out the pixels of objects judged moving; off integrates everything (for comparison).
  bool remove_dynamic = true;
  // Leave out every potentially-moving object (people, animals, vehicles), moving or not.
  bool remove_all_potentially_moving = false;
  // An object judged moving once stays out (its earlier still points are dropped too): a
  // person who stops walking for a moment leaves no ghost.
  bool sticky_moving = true;
  // Masks of left-out objects first grow along their own depth: into neighbouring pixels whose
  // depth continues the object's (a step below flying_pixel_step) and lies within
  // mask_growth_depth_band metres of the object's median depth, at most mask_growth pixels from
  // the mask (0 = no growth). Network masks are late and loose; the object's depth is not.
  int mask_growth = 30;
  double mask_growth_depth_band = 0.4;
  // Then they grow by this many pixels: depth at mask borders belongs to either side.
  int mask_dilation = 4;
  // Flying pixels: a pixel whose depth differs from a 4-neighbour's by more than this fraction
  // of its depth lies on a depth edge, where the sensor mixes both sides; it is left out.
  // 0 keeps them.
  double flying_pixel_step = 0.03;
  // Background depth is averaged over the (2 depthSmoothing + 1)^2 pixels around each pixel
  // that lie on its surface (a step below flying_pixel_step) before it is back-projected, and
  // surface normals are taken over that many pixels: at a few metres a Kinect's depth noise
  // (centimetres) would otherwise spread a wall over the voxel layers in front of and behind
  // it, and the OctoMap would mark the layer in front occupied. 0 = raw depth, normals over
  // 1 pixel. Each point then counts as a view of its voxel with weight cos / z^4: the cosine
  // between its ray and the surface normal (frontal views place a surface best) times the
  // inverse depth variance.
  int depth_smoothing = 2;
  // Evidence (coarse map): a voxel is exported once min_views keyframes saw a point in it.
  // Each view adds one to its evidence and each later keyframe whose depth lies clearly behind
  // it (seen through) takes one away; evidence is clamped to [-evidence_max, evidence_max] so a
  // long-standing object that left is carved away after a bounded number of views. Voxels with
  // evidence <= 0 are not exported. The key-object map needs one view (it is enhanced from
  // several frames) but is carved too.
  int min_views = 3;
  // ... and only once those views span at least min_view_span seconds (first to latest view;
  // 0 = any span): a person who stands still for a moment, or whom the detector misses for a
  // few frames, is seen by several keyframes within a second and plants nothing; one who stays
  // longer is carved away by the views after leaving. Keyframes come fast when people move, so
  // min_views alone does not span much time.
  double min_view_span = 1.0;
  // A keyframe point that a neighbouring frame sees at its depth inside a left-out object's
  // mask is dropped: a detection missed in the keyframe alone plants nothing.
  bool neighbour_veto = true;
  int evidence_max = 3;
  bool carve = true;
  // "Clearly behind": by more than carve_margin + carve_margin_quadratic * depth^2 metres (the
  // depth noise of structured-light sensors grows with the square of depth), over the 3x3
  // pixels around the voxel's projection (depth edges vote nothing).
  double carve_margin = 0.05;
  double carve_margin_quadratic = 0.005;
  // Assembly drops points with fewer occupied neighbouring voxels (of the 26) than this;
  // 0 keeps all.
  int min_neighbours = 1;
  // Keyframes waiting for the dense thread before tracking blocks.
  int queue_capacity = 16;
  // Realtime runs: keyframes waiting for the dense thread before new ones are dropped (and
  // counted). Small, so that the map stays close to the camera and the last keyframes are
  // drained within a second or two when the camera stops.
  int live_queue_capacity = 4;
  // The stored map is re-keyed with the current keyframe poses after this many keyframes, so
  // voxels that pose corrections made coincide merge and memory follows the explored volume.
  int compact_every = 10;
  // dense_map.bt beside dense_map.ply: an OctoMap of occupied and free space at this leaf
  // (metres); 0 writes none.
  double octomap_resolution = 0.05;

  // Throws Error naming the DenseMap.* key of a bad value.
  void Check() const;
};

// Every DenseMap.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<DenseMapOptions>& DenseMapOptionTable();

// Reads DenseMap.* (defaults for absent keys) and checks them; errors name the file and key.
DenseMapOptions LoadDenseMapOptions(const SettingsFile& file);

}  // namespace drvslam
