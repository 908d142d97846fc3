#include "drvslam/core/thread_budget.h"

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <opencv2/core.hpp>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace drvslam {

int ChooseOpenCvThreads(int configured, bool sequential) {
  if (configured > 0) return configured;
  return sequential ? 0 : 1;
}

void ApplyOpenCvThreadBudget(int threads) {
  // OpenCV reads a negative count as "its default"; 0 would mean "no pool" (serial).
  cv::setNumThreads(threads > 0 ? threads : -1);
  spdlog::info("OpenCV thread pool: {} thread(s) ({})", cv::getNumThreads(),
               threads == 1  ? "every stage single-threaded on its own thread"
               : threads > 1 ? "set by Segmentation.dnnThreads, shared by every stage"
                             : "OpenCV's default");
}

int NiceOffset(BackgroundStage stage) {
  // Chosen by realtime runs on 2 cores (README, Real time): the network stays at the tracking
  // thread's priority because late masks cost accuracy (nice 5 tripled the ATE of a walking
  // sequence), while dense mapping, which nothing in the loop waits for, yields the most.
  switch (stage) {
    case BackgroundStage::kLocalMapping:
      return 2;
    case BackgroundStage::kLoopClosing:
      return 4;
    case BackgroundStage::kSegmentation:
      return 0;
    case BackgroundStage::kDenseMapping:
      return 10;
  }
  return 0;
}

void LowerCurrentThreadPriority(BackgroundStage stage) {
#ifdef __linux__
  const int offset = NiceOffset(stage);
  if (offset == 0) return;
  // On Linux, PRIO_PROCESS with a thread id sets that one thread's nice value.
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, tid);
  if (current == -1 && errno != 0) return;
  if (setpriority(PRIO_PROCESS, tid, current + offset) != 0) {
    spdlog::warn("could not lower a background thread's priority: {}", std::strerror(errno));
  }
#else
  (void)stage;
#endif
}

}  // namespace drvslam
