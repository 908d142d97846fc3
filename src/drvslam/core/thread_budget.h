// The process's thread budget. Each pipeline stage is one OS thread of its own: tracking (the
// caller's), segmentation (AsyncSegmenter), local mapping, loop closing and dense mapping; the
// tracking thread has one helper at its own priority that takes pyramid levels of the ORB
// extraction off it when a core is free (ORBextractor.threads, core/side_worker.h).
// OpenCV's parallel_for_ pool is process-global: cv::setNumThreads changes it for cv::dnn on the
// segmentation thread and equally for ORB's pyramid, optical flow and imgproc on the tracking
// thread, and with OpenCV's TBB backend a thread that enters a parallel loop while another
// thread's loop occupies the pool can end up waiting for the pool's workers. So when stages run
// concurrently the pool is set to one thread: every OpenCV call then runs on the thread that made
// it, each stage costs exactly one thread, and the OS scheduler shares the cores between them (on 2
// cores: tracking and the network each get one while mapping and dense mapping sleep, and preempt
// both briefly when a keyframe arrives). A sequential run has one thread only, so there OpenCV
// keeps every core.
#pragma once

namespace drvslam {

// The OpenCV pool size for a run: `configured` (Segmentation.dnnThreads) when positive, else
// 1 for concurrent stages and 0 (OpenCV's default: every core) for a sequential run.
int ChooseOpenCvThreads(int configured, bool sequential);

// Applies the choice (0 = OpenCV's default) once for the process; logs it at info level.
void ApplyOpenCvThreadBudget(int threads);

}  // namespace drvslam

namespace drvslam {

// The threads that run beside tracking. Tracking has a deadline (the next camera frame), so when
// the cores are short the stages whose delay costs least yield to it by running at a lower
// scheduling priority (a higher nice value): the dense map, which nothing in the loop waits for,
// the most; loop closing, which is rare, and local mapping, which has a keyframe's time, a little.
// The network keeps the tracking thread's priority: its masks are only useful while fresh. The
// offsets are kept small because they also count against every other program on the machine. A
// thread that waits for another (tracking waiting for masks, for example) leaves the core to it
// at any priority.
enum class BackgroundStage { kLocalMapping, kLoopClosing, kSegmentation, kDenseMapping };
// The nice offset of a stage's thread against the process's own priority.
int NiceOffset(BackgroundStage stage);
// A thread whose priority was lowered, to give it back later from any thread.
struct ChangedPriority {
  long thread_id = 0;     // the kernel's thread id (0: nothing was lowered)
  int original_nice = 0;  // its nice value before
};
// Lowers the calling thread's priority by NiceOffset(stage). Called first thing by each stage's
// own thread; a sequential run has no such threads. Linux only (nice is per thread there); a
// refusal by the OS is logged and otherwise ignored.
ChangedPriority LowerCurrentThreadPriority(BackgroundStage stage);
// Gives a lowered thread its original priority back, for work that no longer competes with
// tracking (the dense map's last keyframes after the camera stopped). Raising a priority needs
// CAP_SYS_NICE or a RLIMIT_NICE allowance; without them it returns false and nothing changes.
bool RestoreThreadPriority(const ChangedPriority& thread);
}  // namespace drvslam
