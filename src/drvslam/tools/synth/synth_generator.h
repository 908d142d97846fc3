// GenerateSequence: builds a synthetic sequence and writes it to a folder (what `drvslam synth`
// runs). Rendering and PNG writing overlap: writer threads save earlier frames while the next
// one is rendered. Timings are measured but never written into the files, which depend only on the
// options.
#pragma once

#include <functional>
#include <string>

#include "drvslam/tools/synth/synth_options.h"

namespace drvslam::synth {

struct SynthSummary {
  std::string folder;
  std::string scenario;
  std::string static_counterpart;
  std::string path;            // xyz, static, rpy, halfsphere or replay
  std::string texture_source;  // photo folder or "procedural"
  int frames = 0;
  int width = 0, height = 0;
  int actors = 0;
  double setup_seconds = 0.0;  // scene, textures, actor simulation
  double render_fps = 0.0;     // rendering and sensor effects only
  double total_fps = 0.0;      // including writing the PNGs
  double max_coverage = 0.0;   // share of the image covered by actors
  double mean_coverage = 0.0;
  double moving_share = 0.0;  // share of actor-frames flagged as moving
};

// Called after each written frame with (frames done, frames in total), from a writer thread
// (one call at a time).
using SynthProgress = std::function<void(int, int)>;

SynthSummary GenerateSequence(const SynthOptions& options, const std::string& folder,
                              const SynthProgress& progress = {});

}  // namespace drvslam::synth
