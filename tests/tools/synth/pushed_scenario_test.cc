// The pushed_* scenarios: carts, a mover no COCO class names, pushed along the walkers' lanes.
// Each cart is one rigid crate of the stated size that moves and stops, is labelled with its own
// class in the instances and masks, and is listed as a mover in the sequence's settings so that
// ground-truth masks remove it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/tools/synth/synth_sequence.h"

namespace drvslam::synth {
namespace {

SynthOptions PushedOptions(int frames) {
  SynthOptions options;
  options.scenario = "pushed_xyz";
  options.frames = frames;
  options.width = 160;
  options.height = 120;
  options.seed = 2;
  options.sensor = SensorOptions::Clean();
  return options;
}

const SynthSequence& Pushed() {
  static const SynthSequence sequence(PushedOptions(150));
  return sequence;
}

TEST(PushedScenarioTest, CartsAreLabelledWithAClassNoCocoModelNames) {
  const SynthSequence& sequence = Pushed();
  ASSERT_EQ(sequence.Actors().Count(), 2);
  const std::vector<SynthInstance> instances = sequence.Instances();
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(instances[k].class_name, "cart");
    EXPECT_EQ(instances[k].coco_id, -1);
  }
  const std::string yaml = sequence.SettingsExtraYaml();
  EXPECT_NE(yaml.find("Synth.ActorClass: \"cart\""), std::string::npos);
  // The default movers and the carts.
  EXPECT_NE(yaml.find("Segmentation.movingClasses: [\"person\""), std::string::npos);
  EXPECT_NE(yaml.find(", \"cart\"]"), std::string::npos);
}

TEST(PushedScenarioTest, ACartIsOneRigidCrateThatMovesAndStops) {
  const ActorSet& actors = Pushed().Actors();
  for (int k = 0; k < actors.Count(); ++k) {
    int moving = 0;
    for (int f = 0; f < actors.FrameCount(); ++f) {
      const TriangleList triangles = actors.Triangles(k, f);
      ASSERT_EQ(triangles.size(), 12u);  // six faces
      double top = -1e9, bottom = 1e9;
      for (const Triangle& t : triangles) {
        for (const Eigen::Vector3d& p : t.p) {
          top = std::max(top, p.z());
          bottom = std::min(bottom, p.z());
        }
      }
      EXPECT_NEAR(bottom, 0.0, 1e-9);
      EXPECT_NEAR(top, kCartHeight, 1e-9);
      if (actors.Moving(k, f)) ++moving;
      if (f == 0) continue;
      // Rigid: every corner keeps its height and its distance to the first corner.
      const TriangleList before = actors.Triangles(k, f - 1);
      for (std::size_t i = 0; i < triangles.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(triangles[i].p[c].z(), before[i].p[c].z(), 1e-9);
          EXPECT_NEAR((triangles[i].p[c] - triangles[0].p[0]).norm(),
                      (before[i].p[c] - before[0].p[0]).norm(), 1e-9);
        }
      }
    }
    // Five seconds of pushing: it moves in some frames and stands in others.
    EXPECT_GT(moving, 10) << "cart " << k;
    EXPECT_LT(moving, actors.FrameCount()) << "cart " << k;
  }
}

TEST(PushedScenarioTest, TheCartsAreSeenAndMasked) {
  const SynthSequence& sequence = Pushed();
  int frames_with_a_cart = 0;
  for (int f = 0; f < sequence.FrameCount(); f += 10) {
    const RenderBuffers render = sequence.Render(f, false);
    int cart_pixels = 0;
    for (int id = 1; id <= 2; ++id) cart_pixels += cv::countNonZero(render.instance == id);
    if (cart_pixels > 0) ++frames_with_a_cart;
  }
  EXPECT_GE(frames_with_a_cart, 5);
}

TEST(PushedScenarioTest, TheActorClassOptionRelabelsCartsAndIsChecked) {
  SynthOptions options = PushedOptions(5);
  options.actor_class = "suitcase";
  const SynthSequence relabelled(options);
  EXPECT_EQ(relabelled.Instances()[0].class_name, "suitcase");
  EXPECT_EQ(relabelled.Instances()[0].coco_id, 28);
  // A COCO class needs no movingClasses line.
  EXPECT_EQ(relabelled.SettingsExtraYaml().find("Segmentation.movingClasses"), std::string::npos);

  // "cart" names the pushed scenarios' own class (settings.yaml states it) and nothing else.
  options.actor_class = "cart";
  EXPECT_NO_THROW(options.Check());
  options.scenario = "walking_xyz";
  EXPECT_THROW(options.Check(), Error);

  options = PushedOptions(5);
  options.billboards = "cutouts";
  try {
    options.Check();
    FAIL() << "billboards accepted for carts";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("--billboards"), std::string::npos);
  }
}

}  // namespace
}  // namespace drvslam::synth
