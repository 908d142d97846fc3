// drvslam config: what the options registry knows about settings files. --dump writes every key
// at its default with its doc line as a ready settings file; --markdown writes
// docs/configuration.md; --check loads a settings file as `drvslam run` would and reports its
// unknown keys.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dense/grid_options.h"
#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/loop/loop_closing_options.h"
#include "drvslam/loop/relocalization_options.h"
#include "drvslam/mapping/local_mapping_options.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/settings_registry.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam::cli {
namespace {

struct ConfigArguments {
  std::string dump;
  std::string markdown;
  std::string check;
  bool strict = false;
};

// "-" is standard output.
void WriteText(const std::string& text, const std::string& path) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return;
  }
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  out << text;
  out.flush();
  if (!out) throw Error(path + ": write failed");
  std::printf("wrote %s\n", path.c_str());
}

// Loads every section as `drvslam run` does: bad values and (with --strict-settings) unknown
// keys are errors.
void CheckFile(const std::string& path, bool strict) {
  const SettingsFile file(path);
  LoadSettings(file);
  LoadTrackerOptions(file);
  LoadLocalMappingOptions(file);
  LoadRelocalizationOptions(file);
  LoadLoopClosingOptions(file);
  LoadSegmentationOptions(file);
  LoadDynamicOptions(file);
  LoadDenseMapOptions(file);
  LoadGridOptions(file);
  CheckSettingsKeys(file, strict);
  std::printf("%s: settings valid\n", path.c_str());
}

// An option that writes to FILE, or to standard output when FILE is '-' or left out.
void AddOutputOption(CLI::App* command, const std::string& name, std::string* file,
                     const std::string& what) {
  command->add_option(name, *file, what + " (no FILE or '-': standard output)")
      ->expected(0, 1)
      ->default_str("-");
}

const bool kConfigCommandRegistered = RegisterCommand("config", [](CLI::App& root) {
  auto args = std::make_shared<ConfigArguments>();
  CLI::App* command = root.add_subcommand(
      "config", "settings files: dump every key with its default and doc, write the docs, check");
  AddOutputOption(command, "--dump", &args->dump,
                  "write a settings file with every key at its default and its doc line");
  AddOutputOption(command, "--markdown", &args->markdown,
                  "write the settings reference (docs/configuration.md) as Markdown");
  command->add_option("--check", args->check,
                      "load a settings file as `drvslam run` does and report bad or unknown keys");
  command->add_flag("--strict-settings", args->strict,
                    "with --check: unknown keys in drvslam's sections are errors");
  command->callback([command, args] {
    const bool dump = command->count("--dump") > 0;
    const bool markdown = command->count("--markdown") > 0;
    const bool check = !args->check.empty();
    if (dump + markdown + check != 1) {
      throw Error("config: give exactly one of --dump, --markdown and --check");
    }
    if (dump) WriteText(SettingsDump(SettingsSections()), args->dump.empty() ? "-" : args->dump);
    if (markdown) {
      WriteText(SettingsMarkdown(SettingsSections()),
                args->markdown.empty() ? "-" : args->markdown);
    }
    if (check) CheckFile(args->check, args->strict);
  });
});

}  // namespace
}  // namespace drvslam::cli
