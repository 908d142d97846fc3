// What `drvslam benchmark` runs: a list of entries, each a sequence and the way to run it, read
// from a JSON list file or made from command-line options, and checked before any run starts.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "drvslam/tools/runner/sequence_runner.h"

namespace drvslam {

struct BenchmarkEntry {
  std::string name;               // output folder OUT/<name>: letters, digits, '.', '_', '-'
  std::string dataset;            // TUM-layout folder with groundtruth.txt
  std::string config;             // settings file; empty: DATASET/settings.yaml, else TUM fr3
  std::string segmenter;          // yolo|masks|gt|none; empty: chosen as `drvslam run` chooses
  std::string model;              // YOLO ONNX file
  std::string dynamic;            // on|off; empty: on exactly when a segmenter is active
  std::string mode = "threaded";  // threaded|sequential|realtime
  std::string dense;              // on|off; empty: DenseMap.enabled
  std::string loop;               // on|off; empty: LoopClosing.enabled
  std::size_t max_frames = 0;     // 0 = all
  std::optional<int> runs;        // unset: the benchmark's --runs
  // The live viewer (`drvslam run --viewer 0`) with a headless Chromium connected to it for the
  // whole run, so that the report shows what watching costs the tracking thread.
  bool viewer = false;
  // Where the entry came from, for error messages: "LIST: entry 2 (name)" or "--dataset DIR".
  std::string origin;
};

// Reads a JSON list file:
//   {"entries": [{"name": "walking_gt", "dataset": "seq/walking_xyz", "segmenter": "gt"}, ...]}
// Entry keys: name, dataset (required), config, segmenter, model, dynamic, mode, dense, loop
// (strings), max_frames, runs (integers), viewer (true|false). Relative paths (dataset, config,
// model) are taken
// relative to the list file's folder; a missing name is the dataset folder's name. Throws Error
// naming the file, the entry and the key for unreadable JSON, an unknown key or a wrong type.
std::vector<BenchmarkEntry> ReadBenchmarkList(const std::string& path);

// The shortcut without a list: the same options for every dataset.
struct BenchmarkShortcut {
  std::vector<std::string> datasets;
  std::string config;
  std::string segmenter;
  std::string model;
  std::string dynamic;
  std::string mode = "threaded";
  std::string dense;
  std::string loop;
  std::size_t max_frames = 0;
};

// One entry per dataset, named after its folder (made unique with _2, _3, ...).
std::vector<BenchmarkEntry> EntriesFromShortcut(const BenchmarkShortcut& shortcut);

// `drvslam benchmark --viewer-pairs`: after each entry without the viewer, the same entry with it,
// named NAME_viewer, so that each off/on pair runs in one benchmark and sits side by side in its
// tables. Entries that already have the viewer are kept as they are.
std::vector<BenchmarkEntry> WithViewerTwins(const std::vector<BenchmarkEntry>& entries);

// Throws Error naming the entry's origin and the key when an entry cannot run: no entries, a bad
// or repeated name, a missing dataset folder, config or model file, no groundtruth.txt, an
// unknown mode, segmenter or on/off value, or runs below 1. Touches nothing.
void CheckBenchmarkEntries(const std::vector<BenchmarkEntry>& entries);

// What RunSequence gets for one run of the entry, writing into out_dir.
RunOptions ToRunOptions(const BenchmarkEntry& entry, const std::string& out_dir);

// The `drvslam run` command line that does the same as RunSequence(options).
std::string FormatRunCommand(const RunOptions& options);

// `text` as one shell word: unchanged when it is safe, else in single quotes.
std::string ShellQuote(const std::string& text);

}  // namespace drvslam
