// drvslam view: the viewer page for a finished run, served on 127.0.0.1 until Ctrl-C.
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>

#include "command_registry.h"
#include "drvslam/tools/viewer/run_view_server.h"

namespace drvslam::cli {
namespace {

volatile std::sig_atomic_t g_view_stop = 0;

void RequestViewStop(int) { g_view_stop = 1; }

struct ViewOptions {
  std::string run_dir;
  int port = 8080;
  RunDataOptions data;
};

const bool kViewCommandRegistered = RegisterCommand("view", [](CLI::App& root) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command =
      root.add_subcommand("view", "serve the viewer page for a finished run (its output folder)");
  command->add_option("RUN_DIR", options->run_dir, "output folder of drvslam run")->required();
  command->add_option("--port", options->port, "TCP port on 127.0.0.1 (0: any free port)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  command->add_option("--ground-truth", options->data.ground_truth,
                      "TUM ground truth to draw and score against (default: the run's "
                      "DATASET/groundtruth.txt when stats.json names it)");
  command
      ->add_option("--dense-budget", options->data.dense_budget,
                   "dense points sent to the browser at most; a larger map is decimated")
      ->capture_default_str();
  command->callback([options] {
    const RunViewServer server(options->run_dir, options->data, options->port);
    std::signal(SIGINT, RequestViewStop);
    std::signal(SIGTERM, RequestViewStop);
    std::printf("viewer: %s (Ctrl-C to stop)\n", server.Url().c_str());
    std::fflush(stdout);
    while (!g_view_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  });
});

}  // namespace
}  // namespace drvslam::cli
