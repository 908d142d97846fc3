#include "drvslam/core/options_registry.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string_view>

#include "drvslam/core/error.h"
#include "drvslam/core/option_table.h"

namespace drvslam {
namespace {

// A misspelled section ("Dynamics") or top-level key ("DepthMapFactr") counts as ours when it is
// this close to a known one.
constexpr std::size_t kNearName = 2;

std::string Lower(std::string text) {
  for (char& ch : text) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return text;
}

// Levenshtein distance: insertions, deletions and substitutions cost one each.
std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Case differences count less than letters: "largeshare" is nearer "largeShare" than
// "largeShade" is.
std::size_t KeyDistance(const std::string& a, const std::string& b) {
  return 2 * EditDistance(Lower(a), Lower(b)) + (EditDistance(a, b) > 0 ? 1 : 0);
}

std::string SectionOf(const std::string& key) {
  const std::size_t dot = key.find('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string Nearest(const std::string& key, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_distance = 0;
  for (const std::string& candidate : known) {
    const std::size_t distance = KeyDistance(key, candidate);
    if (best.empty() || distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  // Within max(2, a fifth of the key) edits; farther "suggestions" only mislead.
  const std::size_t limit = std::max<std::size_t>(2, key.size() / 5);
  return best_distance <= 2 * limit + 1 ? best : std::string();
}

bool NearAny(const std::string& name, const std::set<std::string>& names) {
  for (const std::string& known : names) {
    if (EditDistance(Lower(name), Lower(known)) <= kNearName) return true;
  }
  return false;
}

std::string Describe(const UnknownSetting& unknown) {
  return "unknown setting " + unknown.key +
         (unknown.suggestion.empty() ? " (no similar key; `drvslam config --dump` lists them all)"
                                     : " (did you mean " + unknown.suggestion + "?)");
}

std::string Cell(const std::string& text) {
  std::string cell;
  for (const char ch : text) {
    if (ch == '|') cell += '\\';
    cell += ch;
  }
  return cell;
}

std::string SectionTitle(const OptionSection& section) {
  return section.name.empty() ? std::string("Top-level keys") : section.name + ".*";
}

}  // namespace

Bounds Bounds::Note(std::string note) const {
  Bounds bounds = *this;
  bounds.note_ = std::move(note);
  return bounds;
}

Bounds Bounds::Min(double min, bool open) const {
  Bounds bounds = *this;
  bounds.has_min_ = true;
  bounds.min_ = min;
  bounds.min_open_ = open;
  return bounds;
}

Bounds Bounds::Max(double max, bool open) const {
  Bounds bounds = *this;
  bounds.has_max_ = true;
  bounds.max_ = max;
  bounds.max_open_ = open;
  return bounds;
}

bool Bounds::Contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (has_min_ && (min_open_ ? value <= min_ : value < min_)) return false;
  if (has_max_ && (max_open_ ? value >= max_ : value > max_)) return false;
  return true;
}

std::string Bounds::Text(bool integer) const {
  const auto number = [](double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return std::string(buffer, result.ptr);
  };
  std::string text;
  if (has_min_ && has_max_) {
    if (integer && !min_open_ && !max_open_) {
      text = number(min_) + ".." + number(max_);
    } else {
      text = std::string(min_open_ ? "(" : "[") + number(min_) + ", " + number(max_) +
             (max_open_ ? ")" : "]");
    }
  } else if (has_min_) {
    text = (min_open_ ? "> " : ">= ") + number(min_);
  } else if (has_max_) {
    text = (max_open_ ? "< " : "<= ") + number(max_);
  }
  if (!note_.empty()) text += (text.empty() ? "" : " ") + ("(" + note_ + ")");
  return text;
}

std::string Bounds::Rule(bool integer) const {
  std::string rule;
  if (has_min_ && has_max_) {
    rule = "must be in " + Text(integer);
  } else if (has_min_ && integer && !min_open_) {
    rule = "must be at least " + Text(integer).substr(3);
  } else if (has_min_ || has_max_) {
    rule = "must be " + Text(integer);
  } else {
    rule = integer ? "must be an integer" : "must be a finite number";
    if (!note_.empty()) rule += " (" + note_ + ")";
  }
  return rule;
}

std::vector<UnknownSetting> FindUnknownSettings(const std::vector<std::string>& keys,
                                                const std::vector<OptionSection>& sections) {
  std::set<std::string> known;
  std::set<std::string> section_names;
  std::set<std::string> top_level;
  std::vector<std::string> all;
  for (const OptionSection& section : sections) {
    if (!section.name.empty()) section_names.insert(section.name);
    for (const OptionInfo& option : section.options) {
      known.insert(option.key);
      all.push_back(option.key);
      if (section.name.empty()) top_level.insert(option.key);
    }
  }
  std::vector<UnknownSetting> unknown;
  for (const std::string& key : keys) {
    if (known.count(key) > 0) continue;
    const std::string section = SectionOf(key);
    const bool ours = section.empty() ? NearAny(key, top_level) : NearAny(section, section_names);
    if (ours) unknown.push_back({key, Nearest(key, all)});
  }
  return unknown;
}

void ReportUnknownSettings(const SettingsFile& file, const std::vector<OptionSection>& sections,
                           bool strict) {
  const std::vector<UnknownSetting> unknown = FindUnknownSettings(file.Keys(), sections);
  if (strict && !unknown.empty()) {
    std::vector<std::string> parts;
    for (const UnknownSetting& setting : unknown) parts.push_back(Describe(setting));
    throw Error(file.Path() + ": " + option_format::Join(parts, "; ") +
                " (--strict-settings makes unknown settings errors)");
  }
  std::set<std::string> reported;
  for (const UnknownSetting& setting : unknown) {
    spdlog::warn("{}: {}, ignored", file.Path(), Describe(setting));
    reported.insert(setting.key);
  }
  for (const std::string& key : file.UnreadKeys()) {
    if (reported.count(key) == 0) spdlog::debug("{}: ignoring setting {}", file.Path(), key);
  }
}

std::string SettingsDump(const std::vector<OptionSection>& sections) {
  std::string text =
      "%YAML:1.0\n"
      "# drvslam settings: every key at its default, written by `drvslam config --dump`.\n"
      "# Keys left out keep these defaults; docs/configuration.md describes them all.\n";
  for (const OptionSection& section : sections) {
    text += "\n# ---- " + SectionTitle(section) + ": " + section.summary + "\n";
    for (const OptionInfo& option : section.options) {
      text += "# " + option.doc + " (" + option.type +
              (option.allowed.empty() ? "" : ", " + option.allowed) + ")\n";
      text += option.key + ": " + option.default_value + "\n";
    }
  }
  return text;
}

std::string SettingsMarkdown(const std::vector<OptionSection>& sections) {
  std::string text =
      "# Configuration\n\n"
      "<!-- Generated from the options registry by `drvslam config --markdown "
      "docs/configuration.md`;\n"
      "     the options_registry_test fails when this file differs from what the code declares. "
      "-->\n\n"
      "drvslam reads one settings file (`drvslam run --config FILE`, else the dataset's\n"
      "`settings.yaml`, else the defaults below: TUM fr3 intrinsics). It is OpenCV FileStorage\n"
      "YAML with flat dotted keys, so ORB-SLAM2 settings files load as they are; drvslam's own\n"
      "sections sit beside the ORB-SLAM2 keys. A key left out keeps its default. A bad value is\n"
      "an error naming the file and the key. An unknown key in one of these sections is warned\n"
      "about with the nearest known key (`did you mean ...?`); `drvslam run --strict-settings`\n"
      "makes it an error. `drvslam config --dump FILE` writes every key at its default, with\n"
      "its description, as a ready settings file; `configs/full_example.yaml` is that file.\n\n"
      "Types: `bool` is 0 or 1 (true/false also read), `int` and `real` are numbers (reals\n"
      "finite), `text` and `path` are strings (a relative `path` is beside the settings file),\n"
      "`list` is `[\"a\", \"b\"]` or one comma-separated string, `choice` is one of the names\n"
      "listed. Ranges: `a..b` integers, `[a, b]` closed and `(a, b)` open intervals.\n";
  for (const OptionSection& section : sections) {
    text += "\n## " + SectionTitle(section) + "\n\n" + section.summary + "\n\n";
    text += "| key | type | default | allowed | description |\n|---|---|---|---|---|\n";
    for (const OptionInfo& option : section.options) {
      text += "| `" + option.key + "` | " + option.type + " | `" + Cell(option.default_value) +
              "` | " + Cell(option.allowed) + " | " + Cell(option.doc) + " |\n";
    }
  }
  return text;
}

namespace option_format {

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const std::string& item : items) {
    if (!text.empty()) text += separator;
    text += item;
  }
  return text;
}

std::string YamlReal(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  // A real written without a point would read back as an integer; keep the type visible.
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

std::string ShownReal(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string YamlText(const std::string& text) {
  std::string quoted = "\"";
  for (const char ch : text) {
    if (ch == '"' || ch == '\\') quoted += '\\';
    quoted += ch;
  }
  return quoted + "\"";
}

std::string YamlList(const std::vector<std::string>& items) {
  std::vector<std::string> quoted;
  for (const std::string& item : items) quoted.push_back(YamlText(item));
  return "[" + Join(quoted, ", ") + "]";
}

std::string ShownList(const std::vector<std::string>& items) {
  std::vector<std::string> quoted;
  for (const std::string& item : items) quoted.push_back("'" + item + "'");
  return "[" + Join(quoted, ", ") + "]";
}

std::string BesideFile(const std::string& path, const std::string& settings_path) {
  if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(settings_path).parent_path() / path).lexically_normal().string();
}

}  // namespace option_format
}  // namespace drvslam
