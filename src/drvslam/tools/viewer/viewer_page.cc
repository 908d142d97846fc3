#include "drvslam/tools/viewer/viewer_page.h"

#include "drvslam/core/error.h"
#include "drvslam/tools/viewer/viewer_assets.h"

namespace drvslam {
namespace {

constexpr char kScriptSlot[] = "<!--DRVSLAM_SCRIPT-->";

std::string WithScript(const std::string& script_html) {
  std::string page(ViewerPage());
  const std::size_t slot = page.find(kScriptSlot);
  if (slot == std::string::npos) throw Error("viewer page: no script slot (build problem)");
  return page.replace(slot, sizeof(kScriptSlot) - 1, script_html);
}

// JSON that is safe inside <script>: '<' only occurs in strings, where \u003c means the same,
// so no "</script>" or "<!--" can end the element early.
std::string ScriptSafeJson(const nlohmann::json& data) {
  const std::string text = data.dump();
  std::string safe;
  safe.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      safe += "\\u003c";
    } else {
      safe += c;
    }
  }
  return safe;
}

}  // namespace

std::string ServedViewerPage() { return WithScript("<script src=\"viewer.js\"></script>"); }

std::string SelfContainedViewerPage(const nlohmann::json& data) {
  std::string html = "<script>window.DRVSLAM_DATA = ";
  html += ScriptSafeJson(data);
  html += ";</script>\n<script>";
  // The bundle has no "</script" (esbuild escapes it in strings), so it is inlined as it is.
  html += ViewerScript();
  html += "</script>";
  return WithScript(html);
}

}  // namespace drvslam
