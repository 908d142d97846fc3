#include "drvslam/core/thread_usage.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifdef __linux__
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace drvslam {

void SortByCpu(std::vector<ThreadUsage>* threads) {
  std::sort(threads->begin(), threads->end(), [](const ThreadUsage& a, const ThreadUsage& b) {
    return a.cpu_s != b.cpu_s ? a.cpu_s > b.cpu_s : a.thread_id < b.thread_id;
  });
}

namespace {

#ifdef __linux__
std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// One thread's files under `task` (/proc/self/task/<tid> or /proc/thread-self); false when
// they were empty or unreadable (a thread that ended while it was read).
bool ReadTask(const std::filesystem::path& task, ThreadUsage* usage) {
  std::string name = ReadText(task / "comm");
  if (name.empty()) return false;
  if (name.back() == '\n') name.pop_back();
  usage->name = name;
  if (!ParseThreadSchedstat(ReadText(task / "schedstat"), usage)) {
    const std::optional<double> cpu =
        ParseCpuSecondsFromStat(ReadText(task / "stat"), sysconf(_SC_CLK_TCK));
    if (!cpu) return false;
    usage->cpu_s = *cpu;
  }
  usage->involuntary_switches = ParseInvoluntarySwitches(ReadText(task / "status"));
  return true;
}

// The threads of the process now; throws only what the standard library throws (bad_alloc).
std::vector<ThreadUsage> ReadTasks(const std::string& caller_name) {
  namespace fs = std::filesystem;
  std::vector<ThreadUsage> threads;
  const long caller = static_cast<long>(syscall(SYS_gettid));
  std::error_code error;
  fs::directory_iterator task("/proc/self/task", error);
  for (; !error && task != fs::directory_iterator(); task.increment(error)) {
    ThreadUsage usage;
    const std::string id = task->path().filename().string();
    char* end = nullptr;
    usage.thread_id = std::strtol(id.c_str(), &end, 10);
    if (end == id.c_str() || *end != '\0') continue;
    if (!ReadTask(task->path(), &usage)) continue;
    if (usage.thread_id == caller) usage.name = caller_name;
    threads.push_back(std::move(usage));
  }
  return threads;
}
#endif

}  // namespace

bool ParseThreadSchedstat(const std::string& schedstat, ThreadUsage* usage) {
  std::istringstream numbers(schedstat);
  long long cpu_ns = 0;
  long long wait_ns = 0;
  if (!(numbers >> cpu_ns >> wait_ns)) return false;
  // Kernels that keep no scheduler statistics print zeros: unknown, not "no CPU".
  if (cpu_ns == 0 && wait_ns == 0) return false;
  usage->cpu_s = 1e-9 * static_cast<double>(cpu_ns);
  usage->runqueue_wait_s = 1e-9 * static_cast<double>(wait_ns);
  return true;
}

std::optional<double> ParseCpuSecondsFromStat(const std::string& stat, long ticks_per_second) {
  // The name field may hold spaces and parentheses: fields count from the last ')'.
  const std::size_t name_end = stat.rfind(')');
  if (name_end == std::string::npos || ticks_per_second <= 0) return std::nullopt;
  std::istringstream fields(stat.substr(name_end + 1));
  std::string field;
  long long utime = 0;
  long long stime = 0;
  // After the name: state is field 3, utime field 14, stime field 15.
  for (int index = 3; index <= 15; ++index) {
    if (!(fields >> field)) return std::nullopt;
    char* end = nullptr;
    const long long value = std::strtoll(field.c_str(), &end, 10);
    if (index >= 14 && (end == field.c_str() || *end != '\0')) return std::nullopt;
    if (index == 14) utime = value;
    if (index == 15) stime = value;
  }
  return static_cast<double>(utime + stime) / static_cast<double>(ticks_per_second);
}

long ParseInvoluntarySwitches(const std::string& status) {
  const std::string key = "nonvoluntary_ctxt_switches:";
  const std::size_t at = status.find(key);
  if (at == std::string::npos) return -1;
  std::istringstream value(status.substr(at + key.size()));
  long switches = -1;
  if (!(value >> switches)) return -1;
  return switches;
}

std::vector<ThreadUsage> UsageSince(const std::vector<ThreadUsage>& earlier,
                                    std::vector<ThreadUsage> now) {
  for (ThreadUsage& thread : now) {
    const auto before = std::find_if(earlier.begin(), earlier.end(), [&](const ThreadUsage& e) {
      return e.thread_id == thread.thread_id;
    });
    // A thread id the kernel gave to a new thread in between: its counts start from zero.
    if (before == earlier.end() || before->cpu_s > thread.cpu_s) continue;
    thread.cpu_s -= before->cpu_s;
    if (thread.runqueue_wait_s && before->runqueue_wait_s) {
      *thread.runqueue_wait_s -= *before->runqueue_wait_s;
    } else {
      thread.runqueue_wait_s.reset();  // unknown at one reading: unknown between them
    }
    thread.involuntary_switches =
        thread.involuntary_switches >= 0 && before->involuntary_switches >= 0
            ? thread.involuntary_switches - before->involuntary_switches
            : -1;
  }
  SortByCpu(&now);
  return now;
}

ThreadUsage ReadCallingThreadUsage() noexcept {
  ThreadUsage usage;
#ifdef __linux__
  try {
    usage.thread_id = static_cast<long>(syscall(SYS_gettid));
    ReadTask("/proc/thread-self", &usage);
  } catch (...) {
    // Figures for a report: what was read is kept.
  }
#endif
  return usage;
}

std::vector<ThreadUsage> ReadThreadUsage(const std::string& caller_name) noexcept {
  std::vector<ThreadUsage> threads;
#ifdef __linux__
  try {
    threads = ReadTasks(caller_name);
  } catch (...) {
    // Figures for a report, never worth a run: none rather than a failure.
    return {};
  }
  SortByCpu(&threads);
#else
  (void)caller_name;
#endif
  return threads;
}

}  // namespace drvslam
