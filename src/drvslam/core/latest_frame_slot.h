// LatestFrameSlot: a camera driver's one-frame hand-off. The producer (a sensor, or a feeder
// thread replaying a dataset at its timestamps) never waits: a new item replaces one that is
// still waiting, and every item replaced that way is counted as skipped. The consumer blocks
// until an item arrives or the slot is closed. Thread-safe: every member is guarded by mutex_.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <utility>

namespace drvslam {

template <typename T>
class LatestFrameSlot {
 public:
  // Never blocks. Returns false (and drops the item) once the slot is closed; an item still
  // waiting is replaced and counted in Skipped().
  bool Put(T item) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return false;
    if (item_) ++skipped_;
    item_ = std::move(item);
    ++accepted_;
    filled_.notify_one();
    return true;
  }

  // Blocks until an item is waiting and takes it; std::nullopt once the slot is closed and
  // empty (an item put before Close is still delivered).
  std::optional<T> Take() {
    std::unique_lock<std::mutex> lock(mutex_);
    filled_.wait(lock, [&] { return closed_ || item_.has_value(); });
    std::optional<T> item = std::move(item_);
    item_.reset();
    return item;
  }

  // Never blocks: the waiting item, or std::nullopt.
  std::optional<T> TryTake() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::optional<T> item = std::move(item_);
    item_.reset();
    return item;
  }

  // Later puts fail; Take returns what is left, then std::nullopt.
  void Close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    filled_.notify_all();
  }

  // Items replaced before anyone took them.
  std::size_t Skipped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return skipped_;
  }
  // Items accepted by Put (taken, skipped or still waiting).
  std::size_t Accepted() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return accepted_;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable filled_;
  std::optional<T> item_;
  bool closed_ = false;
  std::size_t skipped_ = 0;
  std::size_t accepted_ = 0;
};

}  // namespace drvslam
