// Ghosts on a walking scenario: a dense map built with ground-truth poses and masks, from a
// synthetic sequence rendered in memory, against the space the actors swept through.
#include <gtest/gtest.h>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "drvslam/tools/truth/dense_truth.h"
#include "drvslam/tools/truth/synthetic_dense_frame.h"

namespace drvslam {
namespace {

constexpr int kFrames = 90;
constexpr int kKeyFrameEvery = 6;

const synth::SynthSequence& Sequence() {
  static const synth::SynthSequence sequence = [] {
    synth::SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = kFrames;
    options.procedural_textures = true;
    options.width = 320;
    options.height = 240;
    return synth::SynthSequence(options);
  }();
  return sequence;
}

// `evidence` off: every single view plants its points and nothing is carved (the map before
// multi-view confirmation over time and free-space evidence).
DenseTruthScores MapAndScore(bool removal, bool evidence, DenseMapStats* stats) {
  const synth::SynthSequence& sequence = Sequence();
  DenseMapOptions options;
  options.remove_dynamic = removal;
  if (!evidence) {
    options.min_views = 1;
    options.min_view_span = 0.0;
    options.carve = false;
  }
  DenseMapper mapper(sequence.Camera(), options, /*sequential=*/true);
  for (int f = 0; f < sequence.FrameCount(); ++f) {
    DenseFrame frame = RenderDenseFrame(sequence, f);
    if (f % kKeyFrameEvery == 0) {
      mapper.AddKeyFrame(std::move(frame), nullptr);
    } else {
      mapper.AddFrame(std::move(frame));
    }
  }
  mapper.Shutdown();
  const DenseCloud cloud = mapper.Assemble();
  *stats = mapper.Stats();
  return ScoreDenseCloud(cloud, sequence.Scene().triangles, SweptActorGeometry(sequence, 1),
                         KeyObjectLabels(sequence), DenseTruthOptions());
}

TEST(DenseGhosts, RemovalLeavesNoGhostsWhereActorsWalked) {
  DenseMapStats with_stats, without_stats, evidence_stats;
  const DenseTruthScores with_removal = MapAndScore(true, true, &with_stats);
  const DenseTruthScores without_removal = MapAndScore(false, false, &without_stats);
  // Masks off, evidence on: actors never stay long enough in one voxel to be confirmed, and
  // the wall behind them carves what they left.
  const DenseTruthScores evidence_only = MapAndScore(false, true, &evidence_stats);
  RecordProperty("ghost_share_removal_on", std::to_string(with_removal.ghost_share.value_or(-1.0)));
  RecordProperty("ghost_share_removal_off",
                 std::to_string(without_removal.ghost_share.value_or(-1.0)));
  RecordProperty("ghost_share_evidence_only",
                 std::to_string(evidence_only.ghost_share.value_or(-1.0)));
  ASSERT_TRUE(evidence_only.ghost_share.has_value());
  EXPECT_LT(*evidence_only.ghost_share, 0.002);
  EXPECT_EQ(with_stats.keyframes, static_cast<std::size_t>(kFrames / kKeyFrameEvery));
  ASSERT_GT(with_removal.points, 1000u);
  EXPECT_LT(with_removal.ghost_share.value_or(1.0), 0.002);
  EXPECT_GT(without_removal.ghost_share.value_or(0.0), 0.01);
  EXPECT_GT(without_removal.ghosts, 20 * (with_removal.ghosts + 1));
  // Ground-truth poses: the map lies on the true surfaces (depth noise and voxel centroids).
  EXPECT_LT(with_removal.static_mean_distance.value_or(1.0), 0.015);
  EXPECT_LT(with_removal.static_p95_distance.value_or(1.0), 0.05);
  // Compact, yet detailed on the key objects.
  EXPECT_LT(with_stats.exported_points, with_stats.full_resolution_points / 5);
  EXPECT_GT(with_removal.key_object_density.value_or(0.0),
            10.0 * with_removal.background_density.value_or(1e9));
}

}  // namespace
}  // namespace drvslam
