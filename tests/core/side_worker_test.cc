#include "drvslam/core/side_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace drvslam {
namespace {

TEST(SideWorkerTest, EveryItemRunsOnceAndTheHelperTakesSomeWhenItemsTakeTime) {
  SideWorker worker;
  int helper_items = 0;
  for (int round = 0; round < 20; ++round) {
    std::vector<std::atomic<int>> runs(8);
    std::vector<int> thread_of(8, -1);
    worker.ForEach(8, [&](int item, int thread) {
      ++runs[item];
      thread_of[item] = thread;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    });
    for (int i = 0; i < 8; ++i) {
      ASSERT_EQ(runs[i].load(), 1) << "round " << round << " item " << i;
      ASSERT_TRUE(thread_of[i] == 0 || thread_of[i] == 1);
      helper_items += thread_of[i];
    }
  }
  // 2 ms items leave the helper time to join (it sleeps when the machine lends it no core,
  // then the caller does everything; 20 rounds make that unlikely every time).
  EXPECT_GT(helper_items, 0);
}

TEST(SideWorkerTest, AnExceptionReachesTheCallerAndTheWorkerServesAgain) {
  SideWorker worker;
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
  SideWorker worker;
  int helper_runs = 0;
  for (int round = 0; round < 20; ++round) {
    std::atomic<int> runs{0};
    int thread_of = -1;
    worker.Start(1, [&](int, int thread) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      thread_of = thread;
      ++runs;
    });
    EXPECT_TRUE(worker.Started());
    // The caller's own work meanwhile.
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
    worker.Finish();
    EXPECT_FALSE(worker.Started());
    ASSERT_EQ(runs.load(), 1) << "round " << round;
    ASSERT_TRUE(thread_of == 0 || thread_of == 1);
    helper_runs += thread_of;
  }
  // The caller slept 3 ms before Finish: the helper normally took the item.
  EXPECT_GT(helper_runs, 0);
  worker.Finish();  // without a Start: nothing to do
}

TEST(SideWorkerTest, FinishRethrowsAStartedItemsExceptionAndMisuseIsRefused) {
  SideWorker worker;
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
