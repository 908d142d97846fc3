#include "drvslam/core/thread_usage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>

#include "drvslam/core/thread_name.h"
#include "drvslam/core/timing.h"

namespace drvslam {
namespace {

TEST(ThreadUsageTest, ParsesSchedstatInSeconds) {
  ThreadUsage usage;
  ASSERT_TRUE(ParseThreadSchedstat("2500000000 750000000 1234\n", &usage));
  EXPECT_DOUBLE_EQ(usage.cpu_s, 2.5);
  ASSERT_TRUE(usage.runqueue_wait_s.has_value());
  EXPECT_DOUBLE_EQ(*usage.runqueue_wait_s, 0.75);
  ThreadUsage untouched;
  EXPECT_FALSE(ParseThreadSchedstat("", &untouched));
  EXPECT_FALSE(ParseThreadSchedstat("12", &untouched));
  // A kernel without scheduler statistics prints zeros: unknown, not idle.
  EXPECT_FALSE(ParseThreadSchedstat("0 0 0\n", &untouched));
  EXPECT_FALSE(untouched.runqueue_wait_s.has_value());
}

TEST(ThreadUsageTest, ParsesCpuFromStatWhateverTheThreadIsNamed) {
  // Fields after the name: state, ppid, pgrp, session, tty, tpgid, flags, minflt, cminflt,
  // majflt, cmajflt, utime (14), stime (15), ...
  const std::string stat = "4242 (a ) (odd name) S 1 2 3 4 5 6 7 8 9 10 250 50 0 0 20 0\n";
  const std::optional<double> cpu = ParseCpuSecondsFromStat(stat, 100);
  ASSERT_TRUE(cpu.has_value());
  EXPECT_DOUBLE_EQ(*cpu, 3.0);  // (250 + 50) ticks at 100 a second
  EXPECT_FALSE(ParseCpuSecondsFromStat("4242 (short) S 1 2", 100).has_value());
  EXPECT_FALSE(ParseCpuSecondsFromStat("no name field", 100).has_value());
  EXPECT_FALSE(ParseCpuSecondsFromStat(stat, 0).has_value());
}

TEST(ThreadUsageTest, ParsesInvoluntarySwitchesFromStatus) {
  const std::string status =
      "Name:\tdrv-mapping\nState:\tS (sleeping)\nvoluntary_ctxt_switches:\t82\n"
      "nonvoluntary_ctxt_switches:\t1120\n";
  EXPECT_EQ(ParseInvoluntarySwitches(status), 1120);
  EXPECT_EQ(ParseInvoluntarySwitches("Name:\tx\n"), -1);
}

TEST(ThreadUsageTest, UsageSinceSubtractsByThreadAndKeepsNewThreadsWhole) {
  ThreadUsage a{"a", 10, 1.0, 0.5, 3};
  ThreadUsage b{"b", 11, 2.0, std::nullopt, -1};
  ThreadUsage a_now{"a", 10, 4.0, 2.0, 10};
  ThreadUsage b_now{"b", 11, 2.5, 0.25, 7};
  ThreadUsage c_now{"c", 12, 1.0, 0.1, 1};  // started after the first reading
  const std::vector<ThreadUsage> since = UsageSince({a, b}, {b_now, c_now, a_now});
  ASSERT_EQ(since.size(), 3u);
  // By CPU time, most first: a 3.0, c 1.0, b 0.5.
  EXPECT_EQ(since[0].name, "a");
  EXPECT_DOUBLE_EQ(since[0].cpu_s, 3.0);
  EXPECT_DOUBLE_EQ(*since[0].runqueue_wait_s, 1.5);
  EXPECT_EQ(since[0].involuntary_switches, 7);
  EXPECT_EQ(since[1].name, "c");
  EXPECT_DOUBLE_EQ(since[1].cpu_s, 1.0);
  EXPECT_EQ(since[2].name, "b");
  EXPECT_DOUBLE_EQ(since[2].cpu_s, 0.5);
  // Unknown at the first reading: unknown over the interval.
  EXPECT_FALSE(since[2].runqueue_wait_s.has_value());
  EXPECT_EQ(since[2].involuntary_switches, -1);
}

TEST(ThreadUsageTest, AThreadIdReusedInBetweenCountsFromZero) {
  ThreadUsage ended{"old", 10, 5.0, 1.0, 40};
  ThreadUsage reused{"new", 10, 0.5, 0.1, 2};  // less CPU than the id had: another thread
  const std::vector<ThreadUsage> since = UsageSince({ended}, {reused});
  ASSERT_EQ(since.size(), 1u);
  EXPECT_DOUBLE_EQ(since[0].cpu_s, 0.5);
  EXPECT_DOUBLE_EQ(*since[0].runqueue_wait_s, 0.1);
  EXPECT_EQ(since[0].involuntary_switches, 2);
}

#ifdef __linux__
TEST(ThreadUsageTest, ListsTheCallerAndANamedBusyThreadWithItsCpuTime) {
  std::mutex mutex;
  std::condition_variable changed;
  bool spun = false;
  bool release = false;
  std::thread worker([&] {
    NameCurrentThread("drv-usage-test");
    const double start_ms = ThreadCpuMs();
    volatile double sink = 0.0;
    while (ThreadCpuMs() - start_ms < 100.0) sink = sink + 1.0;  // 100 ms of this thread's CPU
    std::unique_lock<std::mutex> lock(mutex);
    spun = true;
    changed.notify_all();
    changed.wait(lock, [&] { return release; });
  });
  {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return spun; });
  }
  // The worker now sleeps, so the kernel has booked all of its CPU time.
  const std::vector<ThreadUsage> threads = ReadThreadUsage("caller");
  {
    std::lock_guard<std::mutex> lock(mutex);
    release = true;
    changed.notify_all();
  }
  worker.join();
  const auto named = [&](const std::string& name) {
    return std::find_if(threads.begin(), threads.end(),
                        [&](const ThreadUsage& t) { return t.name == name; });
  };
  ASSERT_NE(named("caller"), threads.end());
  const auto busy = named("drv-usage-test");
  ASSERT_NE(busy, threads.end());
  EXPECT_GE(busy->cpu_s, 0.05);  // 0.1 s spun; /proc/.../stat books whole clock ticks
  EXPECT_LT(busy->cpu_s, 60.0);  // seconds, not nanoseconds or ticks
  // Where the kernel keeps scheduler statistics, the wait is read, not left unknown.
  std::ifstream own("/proc/thread-self/schedstat");
  std::string own_schedstat;
  std::getline(own, own_schedstat);
  ThreadUsage own_usage;
  if (ParseThreadSchedstat(own_schedstat, &own_usage)) {
    ASSERT_TRUE(busy->runqueue_wait_s.has_value());
    EXPECT_LT(*busy->runqueue_wait_s, 3600.0);  // seconds, not nanoseconds
  }
  for (std::size_t i = 1; i < threads.size(); ++i) {
    EXPECT_GE(threads[i - 1].cpu_s, threads[i].cpu_s) << "sorted by CPU time";
  }
}
#endif

}  // namespace
}  // namespace drvslam
