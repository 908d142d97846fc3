// RunViewServer: `drvslam view RUN_DIR`. Serves the viewer page for a finished run on
// 127.0.0.1: "/" the page, "/viewer.js" its script, "/data/run.json" the run's data (LoadRunData,
// read once at start) and "/files/NAME" the run's output files as they are (the names of
// kRequiredRunFiles and kOptionalRunFiles).
#pragma once

#include <string>

#include "drvslam/tools/viewer/run_data.h"
#include "drvslam/tools/viewer/web_server.h"

namespace drvslam {

class RunViewServer {
 public:
  // Throws Error for a run folder without its outputs (naming the missing files) and for a port
  // in use, before serving anything.
  RunViewServer(const std::string& run_dir, const RunDataOptions& options, int port);

  int Port() const { return server_->Port(); }
  std::string Url() const { return "http://127.0.0.1:" + std::to_string(Port()) + "/"; }

 private:
  std::string run_dir_;
  std::string data_;  // run.json
  std::unique_ptr<WebServer> server_;
};

}  // namespace drvslam
