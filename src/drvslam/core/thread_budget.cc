#include "drvslam/core/thread_budget.h"

#include <spdlog/spdlog.h>

#include <opencv2/core.hpp>

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

}  // namespace drvslam
