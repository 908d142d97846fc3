#include "drvslam/tools/viewer/frame_events.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr const char* kRequiredColumns[] = {"frame", "timestamp", "tracked"};
constexpr const char* kEventColumns[] = {"keyframe", "inliers",      "objects",
                                         "moving",   "movers_share", "features",
                                         "removed",  "unlabelled",   "own_masks"};

std::vector<std::string> SplitTabs(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, '\t')) fields.push_back(field);
  if (!line.empty() && line.back() == '\t') fields.emplace_back();
  return fields;
}

int ColumnIndex(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return static_cast<int>(i);
  }
  return -1;
}

double ParseNumber(const std::string& field, const std::string& where) {
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (field.empty() || end != field.c_str() + field.size()) {
    throw Error(where + ": '" + field + "' is not a number");
  }
  return value;
}

}  // namespace

nlohmann::json ReadFrameEvents(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw Error(path + ": empty, expected a header line");
  const std::vector<std::string> header = SplitTabs(line);
  std::vector<std::pair<std::string, int>> drawn;
  for (const char* name : kRequiredColumns) {
    const int index = ColumnIndex(header, name);
    if (index < 0) throw Error(path + ": header has no '" + name + "' column (not a frame log)");
    drawn.emplace_back(name, index);
  }
  for (const char* name : kEventColumns) {
    const int index = ColumnIndex(header, name);
    if (index >= 0) drawn.emplace_back(name, index);
  }
  nlohmann::json events = nlohmann::json::object();
  for (const auto& [name, index] : drawn) events[name] = nlohmann::json::array();
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::vector<std::string> fields = SplitTabs(line);
    const std::string where = path + " line " + std::to_string(line_number);
    if (fields.size() != header.size()) {
      throw Error(where + ": " + std::to_string(fields.size()) + " fields, the header has " +
                  std::to_string(header.size()));
    }
    for (const auto& [name, index] : drawn) {
      events[name].push_back(ParseNumber(fields[static_cast<std::size_t>(index)], where));
    }
  }
  return events;
}

}  // namespace drvslam
