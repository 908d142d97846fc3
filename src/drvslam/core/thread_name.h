// Names for the threads drvslam starts, so that `top -H`, `perf` and a debugger tell the stages
// apart (every thread otherwise carries the program's name). The caller's own thread, which runs
// tracking, keeps its name: it belongs to the application.
#pragma once

namespace drvslam {

// Names the calling thread. Linux keeps at most 15 characters, so names are short ("drv-mapping");
// a longer one is cut. Does nothing where the platform has no thread names.
void NameCurrentThread(const char* name);

}  // namespace drvslam
