#include "drvslam/core/side_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace drvslam {
namespace {

// Set once by the helper's thread, awaited by the caller's: an order between the two threads
// that holds on any machine (one core, a busy one), where a sleep only makes it likely.
class Signal {
 public:
  void Raise() {
    std::lock_guard<std::mutex> lock(mutex_);
    raised_ = true;
    changed_.notify_all();
  }
  // False only when nothing raised it for 30 s: a hang guard, never reached when the helper
  // takes items (a busy machine delays it by milliseconds).
  bool Await() {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30), [this] { return raised_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool raised_ = false;
};

TEST(SideWorkerTest, EveryItemRunsOnceAndTheHelperTakesSomeWhileTheCallerIsBusy) {
  SideWorker worker("test-helper");
  for (int round = 0; round < 20; ++round) {
    std::vector<std::atomic<int>> runs(8);
    std::vector<int> thread_of(8, -1);
    Signal helper_took_one;
    bool caller_waited = false;
    worker.ForEach(8, [&](int item, int thread) {
      ++runs[item];
      thread_of[item] = thread;
      if (thread == 1) {
        helper_took_one.Raise();
      } else if (!caller_waited) {
        // The caller stays busy with its first item until the helper has joined: the helper
        // takes items offered while the caller works, whenever it gets a core.
        caller_waited = true;
        EXPECT_TRUE(helper_took_one.Await()) << "round " << round;
      }
    });
    int helper_items = 0;
    for (int i = 0; i < 8; ++i) {
      ASSERT_EQ(runs[i].load(), 1) << "round " << round << " item " << i;
      ASSERT_TRUE(thread_of[i] == 0 || thread_of[i] == 1);
      helper_items += thread_of[i];
    }
    EXPECT_GT(helper_items, 0) << "round " << round;
  }
}

TEST(SideWorkerTest, AnExceptionReachesTheCallerAndTheWorkerServesAgain) {
  SideWorker worker("test-helper");
  EXPECT_THROW(worker.ForEach(4,
                              [](int item, int) {
                                if (item == 2) throw std::runtime_error("item 2");
                              }),
               std::runtime_error);
  std::vector<std::atomic<int>> runs(5);
  worker.ForEach(5, [&](int item, int) { ++runs[item]; });
  for (int i = 0; i < 5; ++i) EXPECT_EQ(runs[i].load(), 1) << "item " << i;
  worker.ForEach(0, [](int, int) { FAIL() << "no item to run"; });
}

TEST(SideWorkerTest, StartedItemsRunBesideTheCallerAndFinishWaitsForThem) {
  SideWorker worker("test-helper");
  int helper_runs = 0;
  for (int round = 0; round < 20; ++round) {
    std::atomic<int> runs{0};
    int thread_of = -1;
    Signal ran;
    worker.Start(1, [&](int, int thread) {
      thread_of = thread;
      ++runs;
      ran.Raise();
    });
    EXPECT_TRUE(worker.Started());
    // The caller's own work meanwhile, until the item has run: only the helper can run it
    // before Finish (a sleep here only made that likely on an idle machine).
    EXPECT_TRUE(ran.Await()) << "round " << round;
    worker.Finish();
    EXPECT_FALSE(worker.Started());
    ASSERT_EQ(runs.load(), 1) << "round " << round;
    ASSERT_TRUE(thread_of == 0 || thread_of == 1);
    helper_runs += thread_of;
  }
  // Every item ran beside the caller, before its Finish.
  EXPECT_EQ(helper_runs, 20);
  worker.Finish();  // without a Start: nothing to do
}

TEST(SideWorkerTest, FinishRethrowsAStartedItemsExceptionAndMisuseIsRefused) {
  SideWorker worker("test-helper");
  worker.Start(1, [](int, int) { throw std::runtime_error("flow failed"); });
  EXPECT_THROW(worker.Start(1, [](int, int) {}), std::logic_error);
  EXPECT_THROW(worker.ForEach(1, [](int, int) {}), std::logic_error);
  EXPECT_THROW(worker.Finish(), std::runtime_error);
  // Served again afterwards.
  std::atomic<int> runs{0};
  worker.Start(3, [&](int, int) { ++runs; });
  worker.Finish();
  EXPECT_EQ(runs.load(), 3);
}

}  // namespace
}  // namespace drvslam
