#include "drvslam/tools/synth/synth_generator.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "drvslam/core/bounded_queue.h"
#include "drvslam/core/thread_name.h"
#include "drvslam/tools/synth/scenario.h"
#include "drvslam/tools/synth/sequence_writer.h"
#include "drvslam/tools/synth/synth_sequence.h"

namespace drvslam::synth {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

struct EncodedFrame {
  double stamp = 0.0;
  cv::Mat bgr, depth16, mask16;
};

}  // namespace

SynthSummary GenerateSequence(const SynthOptions& options, const std::string& folder,
                              const SynthProgress& progress) {
  const Clock::time_point start = Clock::now();
  // Refuse bad options or a bad folder before spending seconds on textures.
  options.Check();
  SequenceWriter::CheckFolder(folder);
  const SynthSequence sequence(options);
  const SequenceWriter writer(folder);
  const Clock::time_point ready = Clock::now();

  SynthSummary summary;
  summary.folder = folder;
  summary.scenario = sequence.GetScenario().name;
  summary.static_counterpart = StaticCounterpart(sequence.GetScenario());
  summary.path = PathKindName(sequence.Path().Kind());
  summary.texture_source = sequence.TextureSource();
  summary.frames = sequence.FrameCount();
  summary.width = sequence.Camera().width;
  summary.height = sequence.Camera().height;
  summary.actors = sequence.Actors().Count();
  summary.setup_seconds = Seconds(ready - start);

  // Two writers: encoding a frame's PNGs costs about twice as much CPU as rendering it, and
  // the second writer uses the time the renderer waits for a full queue.
  BoundedQueue<EncodedFrame> queue(4);
  std::mutex error_mutex;
  std::exception_ptr write_error;
  std::atomic<int> written{0};
  const auto write_frames = [&] {
    NameCurrentThread("drv-synth-write");
    while (std::optional<EncodedFrame> frame = queue.Pop()) {
      try {
        writer.WriteFrame(frame->stamp, frame->bgr, frame->depth16, frame->mask16);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!write_error) write_error = std::current_exception();
        queue.Close();
        return;
      }
      const int done = ++written;
      if (progress) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        progress(done, summary.frames);
      }
    }
  };
  std::thread writers[2] = {std::thread(write_frames), std::thread(write_frames)};
  const auto join_writers = [&] {
    for (std::thread& t : writers) t.join();
  };

  double render_seconds = 0.0;
  double coverage_sum = 0.0;
  try {
    for (int f = 0; f < sequence.FrameCount(); ++f) {
      const Clock::time_point before = Clock::now();
      RenderBuffers buffers = sequence.Render(f);
      render_seconds += Seconds(Clock::now() - before);
      const double coverage = sequence.MoverCoverage(buffers.instance);
      summary.max_coverage = std::max(summary.max_coverage, coverage);
      coverage_sum += coverage;
      EncodedFrame frame;
      frame.stamp = sequence.Stamp(f);
      frame.bgr = buffers.bgr;
      frame.depth16 = EncodeDepth(buffers.depth, options.sensor.depth_factor);
      frame.mask16 = buffers.instance;
      if (!queue.Push(std::move(frame))) break;  // the writer failed
    }
  } catch (...) {
    queue.Close();
    join_writers();
    throw;
  }
  queue.Close();
  join_writers();
  if (write_error) std::rethrow_exception(write_error);

  writer.WriteLists(sequence.GroundTruth(), sequence.MakeInstancesFile(), sequence.MakeSettings(),
                    sequence.SettingsExtraYaml());
  const double total_seconds = Seconds(Clock::now() - ready);
  summary.render_fps = render_seconds > 0.0 ? summary.frames / render_seconds : 0.0;
  summary.total_fps = total_seconds > 0.0 ? summary.frames / total_seconds : 0.0;
  summary.mean_coverage = summary.frames > 0 ? coverage_sum / summary.frames : 0.0;
  long long moving = 0;
  for (int k = 0; k < sequence.Actors().Count(); ++k) {
    for (int f = 0; f < summary.frames; ++f) moving += sequence.Actors().Moving(k, f);
  }
  const long long actor_frames = static_cast<long long>(summary.actors) * summary.frames;
  summary.moving_share = actor_frames > 0 ? static_cast<double>(moving) / actor_frames : 0.0;
  return summary;
}

}  // namespace drvslam::synth
