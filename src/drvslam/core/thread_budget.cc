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
  // Chosen by realtime runs on 2 cores (docs/real-time.md). The network keeps the tracking
  // thread's priority because late masks cost accuracy (nice 5 tripled the ATE of a walking
  // sequence); local mapping and loop closing yield a little, the dense map the most. Lowering
  // them further (network 3, local mapping 6, dense 19) freed tracking's core on a quiet
  // machine (0-1 of 300 frames skipped against 6-15) but lost their CPU to other programs on a
  // busy one (ATE 0.38-1.08 cm against 0.22-0.31 beside stress-ng); raising the tracking
  // thread instead (nice -5) doubled the ATE even on a quiet machine.
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

ChangedPriority LowerCurrentThreadPriority(BackgroundStage stage) {
  ChangedPriority lowered;
#ifdef __linux__
  const int offset = NiceOffset(stage);
  if (offset == 0) return lowered;
  // On Linux, PRIO_PROCESS with a thread id sets that one thread's nice value.
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, tid);
  if (current == -1 && errno != 0) return lowered;
  if (setpriority(PRIO_PROCESS, tid, current + offset) != 0) {
    spdlog::warn("could not lower a background thread's priority: {}", std::strerror(errno));
    return lowered;
  }
  lowered.thread_id = static_cast<long>(tid);
  lowered.original_nice = current;
#else
  (void)stage;
#endif
  return lowered;
}

bool RestoreThreadPriority(const ChangedPriority& thread) {
#ifdef __linux__
  if (thread.thread_id == 0) return true;
  if (setpriority(PRIO_PROCESS, static_cast<id_t>(thread.thread_id), thread.original_nice) != 0) {
    spdlog::debug("could not restore a background thread's priority: {}", std::strerror(errno));
    return false;
  }
  return true;
#else
  (void)thread;
  return true;
#endif
}

}  // namespace drvslam
