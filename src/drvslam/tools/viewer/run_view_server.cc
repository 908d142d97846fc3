#include "drvslam/tools/viewer/run_view_server.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "drvslam/tools/viewer/viewer_assets.h"
#include "drvslam/tools/viewer/viewer_page.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

bool IsRunFile(const std::string& name) {
  for (const char* file : kRequiredRunFiles) {
    if (name == file) return true;
  }
  for (const char* file : kOptionalRunFiles) {
    if (name == file) return true;
  }
  return false;
}

std::string ContentType(const std::string& name) {
  const std::string extension = fs::path(name).extension().string();
  if (extension == ".json") return "application/json";
  if (extension == ".txt") return "text/plain; charset=utf-8";
  if (extension == ".tsv") return "text/tab-separated-values; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace

RunViewServer::RunViewServer(const std::string& run_dir, const RunDataOptions& options, int port)
    : run_dir_(run_dir), data_(LoadRunData(run_dir, options).dump()) {
  server_ = std::make_unique<WebServer>(
      port, [this](const std::string& path) -> std::optional<HttpResponse> {
        if (path == "/" || path == "/index.html") {
          return HttpResponse{200, "text/html; charset=utf-8", ServedViewerPage()};
        }
        if (path == "/viewer.js") {
          return HttpResponse{200, "text/javascript; charset=utf-8", std::string(ViewerScript())};
        }
        if (path == "/data/run.json") return HttpResponse{200, "application/json", data_};
        const std::string prefix = "/files/";
        if (path.rfind(prefix, 0) != 0) return std::nullopt;
        // Only the run's named outputs: no path from the request reaches the file system.
        const std::string name = path.substr(prefix.size());
        if (!IsRunFile(name)) return std::nullopt;
        std::ifstream in(fs::path(run_dir_) / name, std::ios::binary);
        if (!in) return std::nullopt;
        return HttpResponse{200, ContentType(name),
                            std::string(std::istreambuf_iterator<char>(in), {})};
      });
}

}  // namespace drvslam
