#include "drvslam/core/thread_usage.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifdef __linux__
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace drvslam {
namespace {

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The CPU time from /proc/.../stat (utime and stime, in clock ticks), for kernels without
// schedstat. The name field may hold spaces and parentheses: fields count from the last ')'.
std::optional<double> CpuSecondsFromStat(const std::string& stat) {
#ifdef __linux__
  const std::size_t name_end = stat.rfind(')');
  if (name_end == std::string::npos) return std::nullopt;
  std::istringstream fields(stat.substr(name_end + 1));
  std::string field;
  long utime = 0;
  long stime = 0;
  // After the name: state is field 3, utime field 14, stime field 15.
  for (int index = 3; index <= 15 && fields >> field; ++index) {
    if (index == 14) utime = std::stol(field);
    if (index == 15) stime = std::stol(field);
  }
  if (!fields) return std::nullopt;
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
#else
  (void)stat;
  return std::nullopt;
#endif
}

}  // namespace

bool ParseThreadSchedstat(const std::string& schedstat, ThreadUsage* usage) {
  std::istringstream numbers(schedstat);
  long long cpu_ns = 0;
  long long wait_ns = 0;
  if (!(numbers >> cpu_ns >> wait_ns)) return false;
  usage->cpu_s = 1e-9 * static_cast<double>(cpu_ns);
  usage->runqueue_wait_s = 1e-9 * static_cast<double>(wait_ns);
  return true;
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

namespace {

void SortByCpu(std::vector<ThreadUsage>* threads) {
  std::sort(threads->begin(), threads->end(), [](const ThreadUsage& a, const ThreadUsage& b) {
    return a.cpu_s != b.cpu_s ? a.cpu_s > b.cpu_s : a.thread_id < b.thread_id;
  });
}

}  // namespace

std::vector<ThreadUsage> UsageSince(const std::vector<ThreadUsage>& earlier,
                                    std::vector<ThreadUsage> now) {
  for (ThreadUsage& thread : now) {
    const auto before = std::find_if(earlier.begin(), earlier.end(), [&](const ThreadUsage& e) {
      return e.thread_id == thread.thread_id;
    });
    if (before == earlier.end()) continue;
    thread.cpu_s -= before->cpu_s;
    if (thread.runqueue_wait_s && before->runqueue_wait_s) {
      *thread.runqueue_wait_s -= *before->runqueue_wait_s;
    }
    if (thread.involuntary_switches >= 0 && before->involuntary_switches >= 0) {
      thread.involuntary_switches -= before->involuntary_switches;
    }
  }
  SortByCpu(&now);
  return now;
}

std::vector<ThreadUsage> ReadThreadUsage(const std::string& caller_name) {
  std::vector<ThreadUsage> threads;
#ifdef __linux__
  namespace fs = std::filesystem;
  const long caller = static_cast<long>(syscall(SYS_gettid));
  std::error_code error;
  for (const fs::directory_entry& task : fs::directory_iterator("/proc/self/task", error)) {
    ThreadUsage usage;
    try {
      usage.thread_id = std::stol(task.path().filename().string());
    } catch (const std::exception&) {
      continue;
    }
    // A thread that ends while it is read leaves empty files: it is left out.
    std::string name = ReadText(task.path() / "comm");
    if (name.empty()) continue;
    if (name.back() == '\n') name.pop_back();
    usage.name = usage.thread_id == caller ? caller_name : name;
    if (!ParseThreadSchedstat(ReadText(task.path() / "schedstat"), &usage)) {
      const std::optional<double> cpu = CpuSecondsFromStat(ReadText(task.path() / "stat"));
      if (!cpu) continue;
      usage.cpu_s = *cpu;
    }
    usage.involuntary_switches = ParseInvoluntarySwitches(ReadText(task.path() / "status"));
    threads.push_back(std::move(usage));
  }
  SortByCpu(&threads);
#else
  (void)caller_name;
#endif
  return threads;
}

}  // namespace drvslam
