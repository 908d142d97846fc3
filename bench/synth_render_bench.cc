// Speed of the synthetic sequence generator: rendering one 640x480 frame (exact geometry, then
// with the default sensor effects, then with each real-camera effect), encoding its three PNGs,
// and building the scene. The render
// benchmarks report process CPU time (all threads) beside wall time, so a loaded machine still
// shows what a frame costs.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "drvslam/tools/synth/sequence_writer.h"
#include "drvslam/tools/synth/synth_sequence.h"

namespace {

using drvslam::synth::RenderBuffers;
using drvslam::synth::SynthOptions;
using drvslam::synth::SynthSequence;

const SynthSequence& Sequence() {
  static const std::unique_ptr<SynthSequence> sequence = [] {
    SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = 300;
    options.opencv_samples = DRVSLAM_OPENCV_DATA_DIR;
    return std::make_unique<SynthSequence>(options);
  }();
  return *sequence;
}

// The benchmark loop: renders every 7th frame, cycling through the sequence; counts fps.
void RenderFrames(benchmark::State& state, const SynthSequence& sequence, bool apply_sensor) {
  int frame = 0;
  for (auto _ : state) {
    RenderBuffers buffers = sequence.Render(frame, apply_sensor);
    benchmark::DoNotOptimize(buffers.bgr.data);
    frame = (frame + 7) % sequence.FrameCount();
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RenderFrame(benchmark::State& state) {
  const SynthSequence& sequence = Sequence();
  RenderFrames(state, sequence, /*apply_sensor=*/false);
}
BENCHMARK(BM_RenderFrame)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_RenderFrameWithSensor(benchmark::State& state) {
  const SynthSequence& sequence = Sequence();
  RenderFrames(state, sequence, /*apply_sensor=*/true);
}
BENCHMARK(BM_RenderFrameWithSensor)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// One frame with one real-camera effect (or all of them, as --real-camera), sensor noise on:
// the cost of each effect against BM_RenderFrameWithSensor.
enum class Effect { kNone, kBlur, kRollingShutter, kDepthShift, kDistortion, kHandheld };

void BM_RenderFrameWithEffect(benchmark::State& state) {
  const Effect effect = static_cast<Effect>(state.range(0));
  SynthOptions options;
  options.scenario = "walking_xyz";
  options.frames = 300;
  options.opencv_samples = DRVSLAM_OPENCV_DATA_DIR;
  drvslam::synth::RealCameraOptions& real = options.real_camera;
  const drvslam::synth::RealCameraOptions handheld = drvslam::synth::HandheldCamera();
  switch (effect) {
    case Effect::kNone:
      state.SetLabel("none");
      break;
    case Effect::kBlur:
      real.blur_exposure = handheld.blur_exposure;
      state.SetLabel("blur, 5 samples");
      break;
    case Effect::kRollingShutter:
      real.rolling_shutter_readout = handheld.rolling_shutter_readout;
      state.SetLabel("rolling shutter, 60 bands");
      break;
    case Effect::kDepthShift:
      real.depth_shift_x = handheld.depth_shift_x;
      real.depth_shift_y = handheld.depth_shift_y;
      state.SetLabel("depth shift 1.5,1");
      break;
    case Effect::kDistortion:
      real.SetDistortion("fr1");
      state.SetLabel("distortion fr1");
      break;
    case Effect::kHandheld:
      real = handheld;
      state.SetLabel("all (--real-camera)");
      break;
  }
  const SynthSequence sequence(options);
  RenderFrames(state, sequence, /*apply_sensor=*/true);
}
BENCHMARK(BM_RenderFrameWithEffect)
    ->DenseRange(0, 5)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_EncodeFramePngs(benchmark::State& state) {
  const RenderBuffers buffers = Sequence().Render(0);
  const cv::Mat depth = drvslam::synth::EncodeDepth(buffers.depth, 5000.0);
  const std::vector<int> parameters = {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY,
                                       cv::IMWRITE_PNG_STRATEGY_RLE};
  std::vector<uchar> bytes;
  for (auto _ : state) {
    cv::imencode(".png", buffers.bgr, bytes, parameters);  // as SequenceWriter writes them
    cv::imencode(".png", depth, bytes, parameters);
    cv::imencode(".png", buffers.instance, bytes, parameters);
    benchmark::DoNotOptimize(bytes.data());
  }
}
BENCHMARK(BM_EncodeFramePngs)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BuildSequence(benchmark::State& state) {
  SynthOptions options;
  options.scenario = "walking_xyz";
  options.frames = 300;
  options.opencv_samples = DRVSLAM_OPENCV_DATA_DIR;
  for (auto _ : state) {
    SynthSequence sequence(options);
    benchmark::DoNotOptimize(sequence.FrameCount());
  }
}
BENCHMARK(BM_BuildSequence)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
