// `drvslam report RUN_DIR`: one self-contained report.html for a finished run, openable offline
// from disk: the viewer page with its script and the run's data inlined (trajectory plots, the
// error over time when there is ground truth, the 3-D map viewer and the stats).
#pragma once

#include <cstddef>
#include <string>

#include "drvslam/tools/viewer/run_data.h"

namespace drvslam {

// Reports inline a smaller dense map than the viewer serves: it is part of the file's size.
inline constexpr std::size_t kReportDenseBudget = 100000;

// Writes the report to out_path (created or replaced) and returns its size in bytes. Throws
// Error as LoadRunData does, or naming out_path when it cannot be written.
std::size_t WriteRunReport(const std::string& run_dir, const std::string& out_path,
                           RunDataOptions options);

}  // namespace drvslam
