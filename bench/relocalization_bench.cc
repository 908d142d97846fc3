// Relocalization cost per attempt where it matters for #31: a saved map of a wall with three
// copies of one photograph and one different photograph (tests/loop/tiled_wall.h), one keyframe
// per copy, so the database proposes every copy. Arg 0: a view of the copies only (ambiguous);
// arg 1: a view of the different photograph (unambiguous). The frame is rebuilt outside the
// timing; the attempt (bag of words, query, matching, PnP, optimization, guided search, the
// choice between places) is timed. Uses only the Relocalizer API ORB-SLAM2's scheme had, so the
// same file measures the code before the change.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "../tests/loop/plane_views.h"
#include "../tests/loop/tiled_wall.h"
#include "drvslam/loop/relocalizer.h"

namespace drvslam {
namespace {

struct WallMap {
  test::PlaneScene scene;
  std::unique_ptr<test::TiledWall> wall;
  KeyFrameDatabase database;
  bool ready = false;

  WallMap() {
    const cv::Mat tile = test::LoadPhoto("graf1.png");
    const cv::Mat unique = test::LoadPhoto("home.jpg");
    if (tile.empty() || unique.empty() || !scene.LoadVocabulary()) return;
    wall = std::make_unique<test::TiledWall>(tile, unique);
    for (int k = 0; k <= test::kRepeats; ++k) {
      const SE3 T_cw = test::WallCamera(test::TiledWall::CentreX(k), 0.0, 0.0, 0.0);
      Frame frame = Build(T_cw);
      frame.SetPose(T_cw);
      auto keyframe = CreateInitialKeyFrame(frame, scene.map, 50);
      if (!keyframe) return;
      scene.ComputeBow(frame);
      keyframe->SetBow(frame.bow, frame.bow_features);
      database.Add(keyframe);
    }
    ready = true;
  }

  Frame Build(const SE3& T_cw) {
    const test::WallView view = wall->Render(scene.settings.camera, T_cw);
    scene.next_timestamp += 1.0;
    return scene.factory.Build(scene.next_timestamp, view.bgr, view.depth);
  }
};

WallMap& SharedWallMap() {
  static WallMap map;
  return map;
}

void BM_RelocalizeOnRepeatedWall(benchmark::State& state) {
  WallMap& map = SharedWallMap();
  if (!map.ready) {
    state.SkipWithError("no default vocabulary or opencv-doc photographs");
    return;
  }
  const double x = state.range(0) == 0 ? 1.26 : 3.5;
  const SE3 T_cw = test::WallCamera(x, 0.02, 0.06, 0.03);
  Relocalizer relocalizer(map.scene.vocabulary, map.database, RelocalizationOptions());
  bool found = false;
  double error = -1.0;
  for (auto _ : state) {
    state.PauseTiming();
    Frame frame = map.Build(T_cw);
    state.ResumeTiming();
    found = relocalizer.Relocalize(frame);
    benchmark::DoNotOptimize(found);
    state.PauseTiming();
    error =
        found ? (frame.Pose().Inverse().Translation() - T_cw.Inverse().Translation()).norm() : -1.0;
    state.ResumeTiming();
  }
  state.counters["found"] = found ? 1 : 0;
  state.counters["error_mm"] = error < 0 ? -1.0 : 1000.0 * error;  // -1: not found
  state.SetLabel(std::string(state.range(0) == 0 ? "copies only" : "different photograph") + ", " +
                 std::to_string(relocalizer.LastReport().candidates) + " candidates, " +
                 std::to_string(relocalizer.LastReport().candidates_tried) + " tried");
}
BENCHMARK(BM_RelocalizeOnRepeatedWall)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
