// Per-frame cost of System::TrackRGBD in sequential mode on a synthetic static sequence rendered
// in memory, so disk and PNG decoding are not measured: the tracking front end alone (ORB
// extraction + tracking, with the place-recognition vocabulary it matches keyframes with; no
// local mapping, no loop closing; second argument 0) and the full pipeline with local mapping
// and loop closing run inline after each keyframe (1). Building the System (vocabulary load) and
// destroying it are not timed. Third argument: rolling-shutter correction and readout estimation
// off (0) or on (1, the default; tracking/rolling_shutter.h). Reports the mean per frame;
// stats.json of `drvslam run` gives median/p95.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/system_stats.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam {
namespace {

struct RenderedFrames {
  Settings settings;
  std::vector<double> stamps;
  std::vector<cv::Mat> bgr;
  std::vector<cv::Mat> depth;
};

const RenderedFrames& Frames() {
  static const RenderedFrames frames = [] {
    synth::SynthOptions options;
    options.scenario = "static_xyz";
    options.frames = 90;
    options.seed = 1;
    const synth::SynthSequence sequence(options);
    RenderedFrames rendered;
    rendered.settings = sequence.MakeSettings();
    for (int i = 0; i < sequence.FrameCount(); ++i) {
      const synth::RenderBuffers buffers = sequence.Render(i);
      rendered.stamps.push_back(sequence.Stamp(i));
      rendered.bgr.push_back(buffers.bgr);
      rendered.depth.push_back(buffers.depth);
    }
    return rendered;
  }();
  return frames;
}

void BM_TrackStaticSequence(benchmark::State& state) {
  const RenderedFrames& frames = Frames();
  Settings settings = frames.settings;
  settings.orb.n_features = static_cast<int>(state.range(0));
  SystemOptions options;
  options.sequential = true;
  const bool full_pipeline = state.range(1) != 0;
  options.mapping.enabled = full_pipeline;
  options.loop.enabled = full_pipeline;
  TrackerOptions tracker_options;
  tracker_options.estimate_readout = state.range(2) != 0;
  long loop_keyframes = 0;
  long local_bas = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto system = std::make_unique<System>(settings, tracker_options, options);
    state.ResumeTiming();
    for (std::size_t i = 0; i < frames.bgr.size(); ++i) {
      system->TrackRGBD(frames.bgr[i], frames.depth[i], frames.stamps[i]);
    }
    state.PauseTiming();
    const SystemStats stats = system->Stats();
    benchmark::DoNotOptimize(stats.tracked);
    // What ran besides tracking: keyframes loop closing looked at, local BAs (0 and 0 for the
    // front end alone).
    loop_keyframes = stats.loop ? stats.loop->keyframes_processed : 0;
    local_bas = stats.mapping.bundle_adjustments;
    system.reset();  // shutdown and freeing the map are no per-frame cost
    state.ResumeTiming();
  }
  state.counters["loop_keyframes"] = static_cast<double>(loop_keyframes);
  state.counters["local_bas"] = static_cast<double>(local_bas);
  state.SetItemsProcessed(state.iterations() * frames.bgr.size());
  // Inverted iteration-invariant rate: elapsed / (iterations * frames / 1000) = ms per frame.
  state.counters["ms_per_frame"] = benchmark::Counter(
      static_cast<double>(frames.bgr.size()) / 1000.0,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TrackStaticSequence)
    ->ArgsProduct({{1000, 2000}, {0, 1}, {0, 1}})
    ->ArgNames({"features", "mapping", "rolling_shutter"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
