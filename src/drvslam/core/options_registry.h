// The settings keys drvslam knows, as plain descriptions (OptionSection) that every module's
// OptionTable (core/option_table.h) produces, and what is built from the whole list: the
// unknown-key check with its "did you mean" suggestion, the ready settings file that
// `drvslam config --dump` writes, and docs/configuration.md.
#pragma once

#include <string>
#include <vector>

#include "drvslam/core/settings_file.h"

namespace drvslam {

// One key as users see it.
struct OptionInfo {
  std::string key;            // "Dynamic.largeShare"
  std::string type;           // bool, int, real, text, path, list or choice
  std::string default_value;  // as a settings file writes it: 0.3, "person", ["a", "b"]
  std::string allowed;        // bounds, choices and rules; empty: any value of the type
  std::string doc;            // one line
};

struct OptionSection {
  std::string name;     // "Dynamic"; empty for top-level keys (ThDepth, DepthMapFactor)
  std::string summary;  // one line
  std::vector<OptionInfo> options;
};

// A key in one of drvslam's sections (or in a section named within two edits of one, or a
// top-level key within two edits of a known one) that no section declares.
struct UnknownSetting {
  std::string key;
  std::string suggestion;  // the nearest known key; empty when none is close
};

// `keys`: the keys of a settings file (SettingsFile::Keys()).
std::vector<UnknownSetting> FindUnknownSettings(const std::vector<std::string>& keys,
                                                const std::vector<OptionSection>& sections);

// Warns about each unknown setting of `file`, naming the nearest known key; with `strict` throws
// one Error naming them all instead. Other keys nobody read are logged at debug level.
void ReportUnknownSettings(const SettingsFile& file, const std::vector<OptionSection>& sections,
                           bool strict);

// A settings file (OpenCV FileStorage YAML, "%YAML:1.0" first) with every key at its default,
// each after a comment holding its doc line, type and allowed values.
std::string SettingsDump(const std::vector<OptionSection>& sections);

// docs/configuration.md: one table per section (key, type, default, allowed, description).
std::string SettingsMarkdown(const std::vector<OptionSection>& sections);

// Formatting shared by OptionTable and the writers above.
namespace option_format {
std::string Join(const std::vector<std::string>& items, const std::string& separator);
// Shortest text that reads back to the same double, with ".0" added when it would read as an
// integer ("40.0", "0.3", "1e-05").
std::string YamlReal(double value);
// A double as an error message shows it (std::ostream's default: 6 significant digits).
std::string ShownReal(double value);
// A double-quoted YAML string.
std::string YamlText(const std::string& text);
std::string YamlList(const std::vector<std::string>& items);
std::string ShownList(const std::vector<std::string>& items);
// `path` when empty or absolute, else the same name in the folder of `settings_path`.
std::string BesideFile(const std::string& path, const std::string& settings_path);
}  // namespace option_format

}  // namespace drvslam
