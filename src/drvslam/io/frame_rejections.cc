#include "drvslam/io/frame_rejections.h"

#include <spdlog/spdlog.h>

#include <utility>

namespace drvslam {

FrameRejections::FrameRejections(std::size_t max_consecutive) : max_consecutive_(max_consecutive) {
  if (max_consecutive_ == 0) throw Error("FrameRejections: max_consecutive must be positive");
}

void FrameRejections::Record(RejectedFrame rejected) {
  ++count_;
  ++by_fault_[FrameFaultName(rejected.fault)];
  if (examples_.size() < kKeptExamples) examples_.push_back(std::move(rejected));
}

void FrameRejections::Reject(std::size_t index, const FrameError& error) {
  spdlog::warn("skipping frame {} ({}): {}", index, FrameFaultName(error.Fault()), error.what());
  std::lock_guard<std::mutex> lock(mutex_);
  Record({index, error.Fault(), error.Path(), error.what()});
  if (++consecutive_ > max_consecutive_) {
    throw Error(std::to_string(consecutive_) +
                " frames in a row could not be used, the sequence is unreadable; the last: " +
                error.what());
  }
}

void FrameRejections::RejectListEntry(const FrameError& error) {
  spdlog::warn("skipping list entry ({}): {}", FrameFaultName(error.Fault()), error.what());
  std::lock_guard<std::mutex> lock(mutex_);
  Record({RejectedFrame::kListEntry, error.Fault(), error.Path(), error.what()});
}

void FrameRejections::Accept() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++accepted_;
  consecutive_ = 0;
}

std::size_t FrameRejections::Count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return count_;
}

std::size_t FrameRejections::Accepted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return accepted_;
}

std::map<std::string, std::size_t> FrameRejections::CountsByFault() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return by_fault_;
}

std::vector<RejectedFrame> FrameRejections::Examples() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return examples_;
}

}  // namespace drvslam
