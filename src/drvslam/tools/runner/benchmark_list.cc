#include "drvslam/tools/runner/benchmark_list.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

const char* const kEntryKeys[] = {"name", "dataset", "config", "segmenter",  "model", "dynamic",
                                  "mode", "dense",   "loop",   "max_frames", "runs",  "viewer"};

bool IsNameCharacter(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
}

// The folder's own name ("walking_xyz" for "data/walking_xyz/"), made a valid entry name.
std::string NameFromFolder(const std::string& folder) {
  fs::path path = fs::path(folder).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") return "sequence";
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !IsNameCharacter(c); }, '_');
  return name;
}

std::string KnownKeys() {
  std::string keys;
  for (const char* key : kEntryKeys) keys += std::string(keys.empty() ? "" : ", ") + key;
  return keys;
}

// `value` relative to the list file's folder unless it is absolute.
std::string NextToList(const fs::path& list_folder, const std::string& value) {
  if (value.empty() || fs::path(value).is_absolute()) return value;
  return (list_folder / value).lexically_normal().string();
}

BenchmarkEntry ParseEntry(const nlohmann::json& json, const std::string& origin,
                          const fs::path& list_folder) {
  if (!json.is_object()) throw Error(origin + ": must be an object {\"dataset\": ...}");
  BenchmarkEntry entry;
  entry.origin = origin;
  const std::map<std::string, std::string*> strings = {
      {"name", &entry.name},           {"dataset", &entry.dataset}, {"config", &entry.config},
      {"segmenter", &entry.segmenter}, {"model", &entry.model},     {"dynamic", &entry.dynamic},
      {"mode", &entry.mode},           {"dense", &entry.dense},     {"loop", &entry.loop}};
  for (const auto& [key, value] : json.items()) {
    const auto text = strings.find(key);
    if (text != strings.end()) {
      if (!value.is_string()) throw Error(origin + ": key '" + key + "' must be a string");
      *text->second = value.get<std::string>();
    } else if (key == "viewer") {
      if (!value.is_boolean()) {
        throw Error(origin + ": key 'viewer' must be true or false (not " + value.dump() + ")");
      }
      entry.viewer = value.get<bool>();
    } else if (key == "runs" || key == "max_frames") {
      if (!value.is_number_integer())
        throw Error(origin + ": key '" + key + "' must be an integer");
      const long long number = value.get<long long>();
      if (key == "runs") {
        // CheckBenchmarkEntries rejects values below 1.
        entry.runs = static_cast<int>(std::clamp<long long>(number, -1, 1000000));
      } else {
        if (number < 0)
          throw Error(origin + ": max_frames = " + std::to_string(number) +
                      " must be 0 (all) or more");
        entry.max_frames = static_cast<std::size_t>(number);
      }
    } else {
      throw Error(origin + ": unknown key '" + key + "' (keys: " + KnownKeys() + ")");
    }
  }
  if (!json.contains("dataset")) throw Error(origin + ": key 'dataset' is missing");
  entry.dataset = NextToList(list_folder, entry.dataset);
  entry.config = NextToList(list_folder, entry.config);
  entry.model = NextToList(list_folder, entry.model);
  if (!json.contains("name")) entry.name = NameFromFolder(entry.dataset);
  entry.origin = origin + " (" + entry.name + ")";
  return entry;
}

void CheckOneOf(const BenchmarkEntry& entry, const char* key, const std::string& value,
                const std::vector<std::string>& allowed, bool empty_allowed) {
  if (empty_allowed && value.empty()) return;
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return;
  std::string choices;
  for (std::size_t i = 0; i < allowed.size(); ++i) {
    choices += (i == 0 ? "" : i + 1 == allowed.size() ? " or " : ", ") + allowed[i];
  }
  throw Error(entry.origin + ": " + key + " = '" + value + "' must be " + choices);
}

void CheckFile(const BenchmarkEntry& entry, const char* key, const std::string& path) {
  std::error_code error;
  if (!path.empty() && !fs::is_regular_file(path, error)) {
    throw Error(entry.origin + ": " + key + " file " + path + " does not exist");
  }
}

void CheckEntry(const BenchmarkEntry& entry) {
  if (entry.name.empty() || entry.name == "." || entry.name == ".." ||
      !std::all_of(entry.name.begin(), entry.name.end(), IsNameCharacter)) {
    throw Error(entry.origin + ": name '" + entry.name +
                "' must be letters, digits, '.', '_' or '-' (it names the output folder)");
  }
  if (entry.dataset.empty()) throw Error(entry.origin + ": dataset is missing");
  std::error_code error;
  if (!fs::is_directory(entry.dataset, error)) {
    throw Error(entry.origin + ": dataset folder " + entry.dataset + " does not exist");
  }
  if (!fs::is_regular_file(fs::path(entry.dataset) / "groundtruth.txt", error)) {
    throw Error(entry.origin + ": dataset " + entry.dataset +
                " has no groundtruth.txt (a benchmark evaluates every run against it)");
  }
  CheckFile(entry, "config", entry.config);
  CheckFile(entry, "model", entry.model);
  CheckOneOf(entry, "mode", entry.mode, {"threaded", "sequential", "realtime"}, false);
  CheckOneOf(entry, "segmenter", entry.segmenter, {"yolo", "masks", "gt", "none"}, true);
  CheckOneOf(entry, "dynamic", entry.dynamic, {"on", "off"}, true);
  CheckOneOf(entry, "dense", entry.dense, {"on", "off"}, true);
  CheckOneOf(entry, "loop", entry.loop, {"on", "off"}, true);
  if (entry.runs && *entry.runs < 1) {
    throw Error(entry.origin + ": runs = " + std::to_string(*entry.runs) + " must be at least 1");
  }
}

}  // namespace

std::vector<BenchmarkEntry> ReadBenchmarkList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the benchmark list");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(path + ": not valid JSON: " + e.what());
  }
  if (!json.is_object()) throw Error(path + ": must be an object {\"entries\": [...]}");
  for (const auto& [key, value] : json.items()) {
    if (key != "entries") throw Error(path + ": unknown key '" + key + "' (only 'entries')");
  }
  const auto entries = json.find("entries");
  if (entries == json.end() || !entries->is_array()) {
    throw Error(path + ": key 'entries' must be a list of entries");
  }
  if (entries->empty()) throw Error(path + ": 'entries' is empty");
  const fs::path list_folder = fs::path(path).parent_path();
  std::vector<BenchmarkEntry> result;
  for (std::size_t i = 0; i < entries->size(); ++i) {
    result.push_back(
        ParseEntry((*entries)[i], path + ": entry " + std::to_string(i + 1), list_folder));
  }
  return result;
}

std::vector<BenchmarkEntry> EntriesFromShortcut(const BenchmarkShortcut& shortcut) {
  std::vector<BenchmarkEntry> entries;
  std::map<std::string, int> uses;
  for (const std::string& dataset : shortcut.datasets) {
    BenchmarkEntry entry;
    entry.dataset = dataset;
    entry.config = shortcut.config;
    entry.segmenter = shortcut.segmenter;
    entry.model = shortcut.model;
    entry.dynamic = shortcut.dynamic;
    entry.mode = shortcut.mode;
    entry.dense = shortcut.dense;
    entry.loop = shortcut.loop;
    entry.max_frames = shortcut.max_frames;
    entry.name = NameFromFolder(dataset);
    const int use = ++uses[entry.name];
    if (use > 1) entry.name += "_" + std::to_string(use);
    entry.origin = "--dataset " + dataset;
    entries.push_back(std::move(entry));
  }
  return entries;
}

std::vector<BenchmarkEntry> WithViewerTwins(const std::vector<BenchmarkEntry>& entries) {
  std::vector<BenchmarkEntry> paired;
  for (const BenchmarkEntry& entry : entries) {
    paired.push_back(entry);
    if (entry.viewer) continue;
    BenchmarkEntry twin = entry;
    twin.name += "_viewer";
    twin.viewer = true;
    twin.origin = entry.origin + " with --viewer-pairs";
    paired.push_back(std::move(twin));
  }
  return paired;
}

void CheckBenchmarkEntries(const std::vector<BenchmarkEntry>& entries) {
  if (entries.empty()) throw Error("benchmark: nothing to run (give --list FILE or --dataset DIR)");
  std::map<std::string, const BenchmarkEntry*> names;
  for (const BenchmarkEntry& entry : entries) {
    CheckEntry(entry);
    const auto [previous, inserted] = names.emplace(entry.name, &entry);
    if (!inserted) {
      throw Error(entry.origin + ": name '" + entry.name + "' is already used by " +
                  previous->second->origin + " (names are output folders)");
    }
  }
}

RunOptions ToRunOptions(const BenchmarkEntry& entry, const std::string& out_dir) {
  RunOptions options;
  options.dataset = entry.dataset;
  options.config = entry.config;
  options.out_dir = out_dir;
  options.sequential = entry.mode == "sequential";
  options.max_frames = entry.max_frames;
  options.dynamic.segmenter = entry.segmenter;
  options.dynamic.model = entry.model;
  options.dynamic.dynamic = entry.dynamic;
  options.dynamic.realtime = entry.mode == "realtime";
  options.dense = entry.dense;
  options.loop = entry.loop;
  if (entry.viewer) options.viewer_port = 0;  // any free port: runs may follow each other quickly
  return options;
}

std::string FormatRunCommand(const RunOptions& options) {
  std::string command = "drvslam run --dataset " + ShellQuote(options.dataset);
  const auto add = [&command](const char* flag, const std::string& value) {
    if (!value.empty()) command += std::string(" ") + flag + " " + ShellQuote(value);
  };
  add("--config", options.config);
  add("--out", options.out_dir);
  if (options.sequential) command += " --sequential";
  if (options.dynamic.realtime) command += " --realtime";
  if (options.max_frames > 0) add("--max-frames", std::to_string(options.max_frames));
  add("--segmenter", options.dynamic.segmenter);
  add("--model", options.dynamic.model);
  add("--dynamic", options.dynamic.dynamic);
  add("--dense", options.dense);
  add("--loop", options.loop);
  if (options.strict_settings) command += " --strict-settings";
  if (options.viewer_port) add("--viewer", std::to_string(*options.viewer_port));
  return command;
}

std::string ShellQuote(const std::string& text) {
  const bool safe = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string("@%+=:,./_-").find(c) != std::string::npos;
  });
  if (safe) return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace drvslam
