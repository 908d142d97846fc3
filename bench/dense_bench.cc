// Dense mapping costs on a 640 x 480 synthetic keyframe (walking_xyz, ground-truth masks):
// our voxel hash against Open3D's VoxelDownSample on the keyframe's full-resolution cloud (the
// choice DenseMapOptions documents), one keyframe's integration with its enhancement frames,
// and assembling the map with the current poses.
#include <benchmark/benchmark.h>

#include <vector>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/open3d_voxel.h"
#include "drvslam/dense/voxel_grid.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "drvslam/tools/truth/synthetic_dense_frame.h"

namespace drvslam {
namespace {

constexpr int kFrames = 60;

const synth::SynthSequence& Sequence() {
  static const synth::SynthSequence sequence = [] {
    synth::SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = kFrames;
    options.procedural_textures = true;
    return synth::SynthSequence(options);
  }();
  return sequence;
}

const std::vector<DenseFrame>& Frames() {
  static const std::vector<DenseFrame> frames = [] {
    std::vector<DenseFrame> all;
    for (int f = 0; f < kFrames; ++f) all.push_back(RenderDenseFrame(Sequence(), f));
    return all;
  }();
  return frames;
}

// Every valid pixel of frame 30 (about 300k points).
const DenseCloud& FullCloud() {
  static const DenseCloud cloud = [] {
    const DenseFrame& frame = Frames()[30];
    DenseMapOptions options;
    options.remove_dynamic = false;
    const PixelRoles roles = PaintRoles(frame, options);
    return BackProject(frame, roles, PixelRole::kBackground, Sequence().Camera(), options);
  }();
  return cloud;
}

// The full cloud downsampled by `downsample` (ours or Open3D's) at a leaf of range(0) mm.
void BM_VoxelDownsample(benchmark::State& state,
                        DenseCloud (*downsample)(const DenseCloud&, double)) {
  const DenseCloud& cloud = FullCloud();
  const double leaf = state.range(0) / 1000.0;
  std::size_t kept = 0;
  for (auto _ : state) {
    const DenseCloud out = downsample(cloud, leaf);
    kept = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["points_in"] = static_cast<double>(cloud.size());
  state.counters["points_out"] = static_cast<double>(kept);
}
BENCHMARK_CAPTURE(BM_VoxelDownsample, Own, &VoxelDownsample)
    ->Arg(5)
    ->Arg(30)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelDownsample, Open3d, &Open3dVoxelDownsample)
    ->Arg(5)
    ->Arg(30)
    ->Unit(benchmark::kMillisecond);

// Isolated-point removal on the downsampled keyframe: our voxel-neighbour count against
// Open3D's statistical filter (k = 20, 2 sigma).
void BM_OutliersOwn(benchmark::State& state) {
  const DenseCloud coarse = VoxelDownsample(FullCloud(), 0.03);
  for (auto _ : state) benchmark::DoNotOptimize(RemoveIsolatedPoints(coarse, 0.03, 1).size());
  state.counters["points_in"] = static_cast<double>(coarse.size());
}
BENCHMARK(BM_OutliersOwn)->Unit(benchmark::kMillisecond);

void BM_OutliersOpen3d(benchmark::State& state) {
  const DenseCloud coarse = VoxelDownsample(FullCloud(), 0.03);
  for (auto _ : state) {
    benchmark::DoNotOptimize(Open3dStatisticalOutlierRemoval(coarse, 20, 2.0).size());
  }
  state.counters["points_in"] = static_cast<double>(coarse.size());
}
BENCHMARK(BM_OutliersOpen3d)->Unit(benchmark::kMillisecond);

// One keyframe (every 10th frame) with its 4 enhancement frames (2 before, 2 after), on a map
// of the earlier ones: carving, back-projection, key-object enhancement and insertion.
void BM_IntegrateKeyFrame(benchmark::State& state) {
  const std::vector<DenseFrame>& frames = Frames();
  const CameraOptions& camera = Sequence().Camera();
  for (auto _ : state) {
    state.PauseTiming();
    DenseMapper mapper(camera, DenseMapOptions(), /*sequential=*/true);
    for (int f = 0; f < 50; ++f) {
      if (f % 10 == 0) {
        mapper.AddKeyFrame(frames[f], nullptr);
      } else {
        mapper.AddFrame(frames[f]);
      }
    }
    for (int f = 50; f < 59; ++f) mapper.AddFrame(frames[f]);
    state.ResumeTiming();
    mapper.AddKeyFrame(frames[59], nullptr);
    mapper.Shutdown();  // integrates it without the frames after it
  }
}
BENCHMARK(BM_IntegrateKeyFrame)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_Assemble(benchmark::State& state) {
  const std::vector<DenseFrame>& frames = Frames();
  DenseMapper mapper(Sequence().Camera(), DenseMapOptions(), true);
  for (int f = 0; f < kFrames; ++f) {
    if (f % 10 == 0) {
      mapper.AddKeyFrame(frames[f], nullptr);
    } else {
      mapper.AddFrame(frames[f]);
    }
  }
  std::size_t points = 0;
  for (auto _ : state) points = mapper.Assemble().size();
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_Assemble)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
