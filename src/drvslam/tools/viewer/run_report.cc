#include "drvslam/tools/viewer/run_report.h"

#include <fstream>

#include "drvslam/core/error.h"
#include "drvslam/tools/viewer/viewer_page.h"

namespace drvslam {

std::size_t WriteRunReport(const std::string& run_dir, const std::string& out_path,
                           RunDataOptions options) {
  options.mode = "report";
  const std::string html = SelfContainedViewerPage(LoadRunData(run_dir, options));
  std::ofstream out(out_path, std::ios::binary);
  if (!out) throw Error(out_path + ": cannot open for writing");
  out << html;
  if (!out) throw Error(out_path + ": write failed");
  return html.size();
}

}  // namespace drvslam
