#include "drvslam/core/thread_budget.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <opencv2/core.hpp>
#include <thread>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace drvslam {
namespace {

TEST(ThreadBudgetTest, ConcurrentStagesGetOneOpenCvThreadSequentialKeepsTheDefault) {
  EXPECT_EQ(ChooseOpenCvThreads(0, false), 1);
  EXPECT_EQ(ChooseOpenCvThreads(0, true), 0);
  EXPECT_EQ(ChooseOpenCvThreads(3, false), 3);
  EXPECT_EQ(ChooseOpenCvThreads(3, true), 3);
}

TEST(ThreadBudgetTest, AppliesToOpenCvsProcessWidePool) {
  const int original = cv::getNumThreads();
  ApplyOpenCvThreadBudget(1);
  EXPECT_EQ(cv::getNumThreads(), 1);
  ApplyOpenCvThreadBudget(0);
  EXPECT_EQ(cv::getNumThreads(), original);
}

TEST(ThreadBudgetTest, DenseMappingYieldsMostTheNetworkNot) {
  EXPECT_EQ(NiceOffset(BackgroundStage::kSegmentation), 0);
  EXPECT_GT(NiceOffset(BackgroundStage::kLocalMapping), 0);
  EXPECT_GT(NiceOffset(BackgroundStage::kLoopClosing), NiceOffset(BackgroundStage::kLocalMapping));
  EXPECT_GT(NiceOffset(BackgroundStage::kDenseMapping), NiceOffset(BackgroundStage::kLoopClosing));
}

#ifdef __linux__
int ThisThreadsNice() { return getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid))); }

TEST(ThreadBudgetTest, LowersOnlyTheCallingThread) {
  const int caller_before = ThisThreadsNice();
  int stage_before = 0;
  int stage_after = 0;
  std::thread stage([&] {
    stage_before = ThisThreadsNice();
    LowerCurrentThreadPriority(BackgroundStage::kDenseMapping);
    stage_after = ThisThreadsNice();
  });
  stage.join();
  // Nice values stop at 19.
  const int expected = std::min(19, stage_before + NiceOffset(BackgroundStage::kDenseMapping));
  EXPECT_EQ(stage_after, expected);
  EXPECT_EQ(ThisThreadsNice(), caller_before);
}

TEST(ThreadBudgetTest, AnotherThreadCanRestoreAChangedPriority) {
  std::mutex mutex;
  std::condition_variable changed;
  ChangedPriority lowered;
  bool ready = false;
  bool restored = false;
  int nice_before = 0;
  int nice_lowered = 0;
  int nice_restored = 0;
  std::thread stage([&] {
    const int before = ThisThreadsNice();
    nice_before = before;
    ChangedPriority mine = LowerCurrentThreadPriority(BackgroundStage::kLocalMapping);
    nice_lowered = ThisThreadsNice() - before;
    std::unique_lock<std::mutex> lock(mutex);
    lowered = mine;
    ready = true;
    changed.notify_all();
    changed.wait(lock, [&] { return restored; });
    nice_restored = ThisThreadsNice() - before;
  });
  bool raised = false;
  {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return ready; });
    EXPECT_NE(lowered.thread_id, 0);
    raised = RestoreThreadPriority(lowered);
    restored = true;
    changed.notify_all();
  }
  stage.join();
  // Nice values stop at 19: a test started under `nice -n 19` (or any nice above
  // 19 - offset) lowers by less, by nothing at 19.
  EXPECT_EQ(nice_lowered, std::min(NiceOffset(BackgroundStage::kLocalMapping), 19 - nice_before));
  // Raising a priority needs CAP_SYS_NICE (root has it): without it nothing changes.
  EXPECT_EQ(nice_restored, raised ? 0 : nice_lowered);
  if (geteuid() == 0) {
    EXPECT_TRUE(raised);
  }
}
#endif

}  // namespace
}  // namespace drvslam
