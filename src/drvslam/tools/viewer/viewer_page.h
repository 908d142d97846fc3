// The viewer page in its two forms: served (the script fetched from /viewer.js) and
// self-contained (script and run data inlined: drvslam report).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace drvslam {

// The page as WebServer serves it at "/": the script comes from "/viewer.js".
std::string ServedViewerPage();

// One HTML file that needs nothing else: the script and `data` (LoadRunData's JSON, mode
// "report") inlined.
std::string SelfContainedViewerPage(const nlohmann::json& data);

}  // namespace drvslam
