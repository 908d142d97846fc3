// How much CPU each of the process's threads has had, and how long each waited for a core. On a
// machine with fewer cores than busy threads, a stage that misses its deadline (tracking skipping
// camera frames) is either doing too much work or not getting a core: the two need different
// fixes, and these figures tell which. Threads are told apart by their names (core/thread_name.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace drvslam {

struct ThreadUsage {
  std::string name;  // the thread's name; `caller_name` for the thread that asked
  long thread_id = 0;
  double cpu_s = 0.0;  // CPU time used since the thread started
  // Time the thread was ready to run but waited for a core (Linux schedstat); absent where the
  // kernel does not keep it.
  std::optional<double> runqueue_wait_s;
  // Times the scheduler took the core away while the thread still had work (a thread that
  // waits for a lock or a queue gives its core up voluntarily: not counted). -1: unknown.
  long involuntary_switches = -1;
};

// Every thread the process has now, from /proc/self/task, by CPU time (most first); the calling
// thread is named `caller_name`. Threads that have ended are not listed. Empty where /proc is not
// available (not Linux) or cannot be read.
std::vector<ThreadUsage> ReadThreadUsage(const std::string& caller_name) noexcept;

// The calling thread's usage so far, named by its thread name; for a thread to record just
// before it ends (its /proc entry goes with it). cpu_s 0 and nothing else known where /proc
// cannot be read.
ThreadUsage ReadCallingThreadUsage() noexcept;

// Orders by CPU time, most first (ties by thread id).
void SortByCpu(std::vector<ThreadUsage>* threads);

// What each thread used between two readings: `now` less `earlier`, matched by thread id (a
// thread that started in between counts from zero), by CPU time (most first). A figure unknown
// at either reading is unknown in the result.
std::vector<ThreadUsage> UsageSince(const std::vector<ThreadUsage>& earlier,
                                    std::vector<ThreadUsage> now);

// Parsers of /proc/<pid>/task/<tid>/ files, for ReadThreadUsage:
// schedstat ("cpu_ns wait_ns slices") into usage's cpu_s and runqueue_wait_s; false when it does
// not hold two numbers or holds only zeros (a kernel that keeps no scheduler statistics).
bool ParseThreadSchedstat(const std::string& schedstat, ThreadUsage* usage);
// stat's utime + stime in seconds, for kernels without schedstat.
std::optional<double> ParseCpuSecondsFromStat(const std::string& stat, long ticks_per_second);
// status's nonvoluntary_ctxt_switches; -1 when absent.
long ParseInvoluntarySwitches(const std::string& status);

}  // namespace drvslam
