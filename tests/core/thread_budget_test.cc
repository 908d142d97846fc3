#include "drvslam/core/thread_budget.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

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

}  // namespace
}  // namespace drvslam
