// FrameRejections: the frames a run skipped because they could not be used (FrameError), with
// one warning each, counts per fault for stats.json, and a limit on rejections in a row: a camera
// that hiccups loses a frame, a sequence that cannot be read at all stops the run.
// Thread-safe: a loader thread may reject while the run reads the counts.
#pragma once

#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "drvslam/io/frame_fault.h"

namespace drvslam {

struct RejectedFrame {
  static constexpr std::size_t kListEntry = static_cast<std::size_t>(-1);
  std::size_t index = kListEntry;  // frame index, or kListEntry for a list line dropped on open
  FrameFault fault = FrameFault::kCorruptImage;
  std::string path;
  std::string message;
};

class FrameRejections {
 public:
  // The examples kept for stats.json: the first ones, so memory stays bounded over hours.
  static constexpr std::size_t kKeptExamples = 20;

  // max_consecutive > 0: the most frames in a row that may be rejected before Reject throws.
  explicit FrameRejections(std::size_t max_consecutive);

  // Frame `index` could not be used: logs one warning and counts it. Throws Error (naming the
  // last file) when this makes more than max_consecutive rejections in a row.
  void Reject(std::size_t index, const FrameError& error);
  // A list entry dropped when the sequence was opened (TumDataset::DroppedEntries): logged and
  // counted, never part of a run of rejections.
  void RejectListEntry(const FrameError& error);
  // Frame loaded fine: ends the current run of rejections.
  void Accept();

  std::size_t Count() const;
  std::size_t Accepted() const;
  // Counts per FrameFaultName; faults that did not occur are absent.
  std::map<std::string, std::size_t> CountsByFault() const;
  // The first kKeptExamples rejections, in order.
  std::vector<RejectedFrame> Examples() const;

 private:
  void Record(RejectedFrame rejected);

  const std::size_t max_consecutive_;
  mutable std::mutex mutex_;  // guards everything below
  std::size_t count_ = 0;
  std::size_t accepted_ = 0;
  std::size_t consecutive_ = 0;
  std::map<std::string, std::size_t> by_fault_;
  std::vector<RejectedFrame> examples_;
};

}  // namespace drvslam
