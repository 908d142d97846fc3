// SideWorker: one persistent thread that helps the calling thread through a list of
// independent work items (the ORB extractor's pyramid levels), or runs one job beside the
// caller's own work (the dynamic stage's optical flow while the extractor runs). Both threads take
// items from a shared counter, so on a busy machine, where the helper may get no core for a while,
// the caller simply does every item itself: it never waits for a helper that has not started. A
// persistent thread, not one per call: a frame needs two hand-offs, and starting threads 60 times a
// second would cost more than the split saves. The helper starts with the creating thread's
// scheduling priority (Linux threads inherit the nice value): the tracking thread's helper runs at
// the tracking thread's priority.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace drvslam {

class SideWorker {
 public:
  // `name` names the helper thread (core/thread_name.h).
  explicit SideWorker(const char* name);
  // Joins the helper.
  ~SideWorker();
  SideWorker(const SideWorker&) = delete;
  SideWorker& operator=(const SideWorker&) = delete;

  // Calls item(i, thread) for every i in [0, count), each exactly once, on the calling thread
  // (thread 0) and on the helper (thread 1) when it joins in time; items are taken in order.
  // Returns when every item is done. The first exception thrown by an item is rethrown here
  // (items not yet taken are then skipped). One caller at a time.
  void ForEach(int count, const std::function<void(int item, int thread)>& item);

  // ForEach in two halves, for work the caller overlaps with work of its own: Start offers the
  // items (kept by value) and returns at once; Finish takes whatever the helper has not taken
  // (all of it when the helper got no core), waits for the helper's items and rethrows the
  // first exception. Every Start needs its Finish before the next Start or ForEach; Finish
  // without a Start returns at once.
  void Start(int count, std::function<void(int item, int thread)> item);
  void Finish();
  bool Started() const { return started_; }

 private:
  void Loop();
  // Takes items until none is left; returns the exception of the one that threw, if any.
  std::exception_ptr TakeItems(int thread);

  std::mutex mutex_;
  std::condition_variable changed_;
  // Offers the items at item_ (the caller keeps them alive until Finish).
  void Offer(const std::function<void(int, int)>* item, int count);

  // The current call, read by the helper once it took the call (under mutex_).
  const std::function<void(int, int)>* item_ = nullptr;
  std::function<void(int, int)> started_item_;  // Start's items
  bool started_ = false;                        // a Start waits for its Finish (caller only)
  int count_ = 0;
  std::atomic<int> next_{0};
  bool offered_ = false;  // a call waits for the helper to join
  bool helping_ = false;  // the helper took the call and works on it
  bool stopping_ = false;
  std::exception_ptr helper_error_;
  std::thread thread_;
};

}  // namespace drvslam
