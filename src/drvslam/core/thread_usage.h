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
// available (not Linux).
std::vector<ThreadUsage> ReadThreadUsage(const std::string& caller_name);

// What each thread used between two readings: `now` less `earlier`, matched by thread id (a
// thread that started in between counts from zero), by CPU time (most first).
std::vector<ThreadUsage> UsageSince(const std::vector<ThreadUsage>& earlier,
                                    std::vector<ThreadUsage> now);

// Parses the text of /proc/<pid>/task/<tid>/schedstat ("cpu_ns wait_ns slices") and of its
// status file (the nonvoluntary_ctxt_switches line) into `usage`. False when schedstat does not
// hold two numbers.
bool ParseThreadSchedstat(const std::string& schedstat, ThreadUsage* usage);
long ParseInvoluntarySwitches(const std::string& status);

}  // namespace drvslam
