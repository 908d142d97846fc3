#include "drvslam/core/thread_name.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "drvslam/core/side_worker.h"

#ifdef __linux__
#include <pthread.h>
#endif

namespace drvslam {
namespace {

#ifdef __linux__
std::string CurrentThreadName() {
  char name[32] = {};
  EXPECT_EQ(pthread_getname_np(pthread_self(), name, sizeof(name)), 0);
  return name;
}

TEST(ThreadNameTest, NamesTheCallingThreadOnly) {
  std::string inside;
  const std::string caller_before = CurrentThreadName();
  std::thread thread([&] {
    NameCurrentThread("drv-test");
    inside = CurrentThreadName();
  });
  thread.join();
  EXPECT_EQ(inside, "drv-test");
  EXPECT_EQ(CurrentThreadName(), caller_before);
}

TEST(ThreadNameTest, CutsNamesLongerThanLinuxKeeps) {
  std::string inside;
  std::thread thread([&] {
    NameCurrentThread("drv-a-name-that-is-too-long");
    inside = CurrentThreadName();
  });
  thread.join();
  EXPECT_EQ(inside, "drv-a-name-that");  // the first 15 characters
}

TEST(ThreadNameTest, SideWorkerHelperCarriesItsName) {
  SideWorker worker("drv-helper-test");
  std::mutex mutex;
  std::condition_variable changed;
  std::string helper_name;
  worker.ForEach(2, [&](int, int thread) {
    std::unique_lock<std::mutex> lock(mutex);
    if (thread == 1) {
      helper_name = CurrentThreadName();
      changed.notify_all();
    } else {
      // The caller holds its first item until the helper has taken the other (30 s guards
      // against a hang; a busy machine delays the helper by milliseconds).
      changed.wait_for(lock, std::chrono::seconds(30), [&] { return !helper_name.empty(); });
    }
  });
  EXPECT_EQ(helper_name, "drv-helper-test");
}
#endif

}  // namespace
}  // namespace drvslam
