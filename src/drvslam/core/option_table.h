// OptionTable: the one place a module declares its settings keys. Each key is declared once,
// bound to its options-struct field: name, type, bounds (or allowed values) and a one-line doc;
// its default is the field's initializer. Loading, range checking, `drvslam config --dump`,
// docs/configuration.md and the unknown-key warning (core/options_registry.h) all read the table.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/core/options_registry.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

// The allowed values of a number key: an interval whose ends are each closed, open or absent.
// Reals must also be finite.
class Bounds {
 public:
  static Bounds Any() { return Bounds(); }
  static Bounds AtLeast(double min) { return Bounds().Min(min, false); }             // [min, inf)
  static Bounds Above(double min) { return Bounds().Min(min, true); }                // (min, inf)
  static Bounds In(double min, double max) { return AtLeast(min).Max(max, false); }  // [min, max]
  static Bounds AboveUpTo(double min, double max) { return Above(min).Max(max, false); }  // (, ]
  static Bounds AtLeastBelow(double min, double max) {
    return AtLeast(min).Max(max, true);
  }                                                                                    // [, )
  static Bounds Between(double min, double max) { return Above(min).Max(max, true); }  // (min, max)
  // Said after the rule in errors and docs, e.g. "0 = off" or "pixels".
  Bounds Note(std::string note) const;

  bool Contains(double value) const;
  // "1..32", "[0, 1]", ">= 8", "> 0"; empty for Any().
  std::string Text(bool integer) const;
  // "must be in 1..32", "must be at least 8", "must be > 0", "must be a finite number", with the
  // note in parentheses.
  std::string Rule(bool integer) const;

 private:
  Bounds Min(double min, bool open) const;
  Bounds Max(double max, bool open) const;

  bool has_min_ = false, has_max_ = false, min_open_ = false, max_open_ = false;
  double min_ = 0.0, max_ = 0.0;
  std::string note_;
};

// Settings spellings of an enum's values, in the order docs list them.
template <typename Enum>
using Choices = std::vector<std::pair<std::string, Enum>>;

// The value `text` names; throws Error("<key> = '<text>' must be one of a, b, c") otherwise.
template <typename Enum>
Enum ParseChoice(const std::string& text, const std::string& key, const Choices<Enum>& choices) {
  std::vector<std::string> names;
  for (const auto& [name, value] : choices) {
    if (name == text) return value;
    names.push_back(name);
  }
  throw Error(key + " = '" + text + "' must be one of " + option_format::Join(names, ", "));
}

template <typename Enum>
std::string ChoiceName(Enum value, const Choices<Enum>& choices) {
  for (const auto& [name, choice] : choices) {
    if (choice == value) return name;
  }
  return "?";
}

template <typename Options>
class OptionTable {
 public:
  // `section` prefixes every key ("Dynamic" gives "Dynamic.largeShare"); empty for top-level
  // keys. `summary` is the section's one line in docs and dumps.
  OptionTable(std::string section, std::string summary)
      : section_(std::move(section)), summary_(std::move(summary)) {}

  // Accepts 0/1 numbers and true/false strings.
  OptionTable& Bool(const char* name, bool Options::*field, const char* doc) {
    Entry& entry = Add(name, "bool", "", doc);
    entry.read = [key = entry.key, field](const SettingsFile& file, Options& o) {
      o.*field = file.GetBool(key, o.*field);
    };
    entry.shown = [field](const Options& o) { return std::string(o.*field ? "1" : "0"); };
    entry.yaml = entry.shown;
    return *this;
  }

  OptionTable& Int(const char* name, int Options::*field, const Bounds& bounds, const char* doc) {
    Entry& entry = Add(name, "int", bounds.Text(true), doc);
    entry.read = [key = entry.key, field](const SettingsFile& file, Options& o) {
      o.*field = file.GetInt(key, o.*field);
    };
    entry.ok = [field, bounds](const Options& o) { return bounds.Contains(o.*field); };
    entry.rule = bounds.Rule(true);
    entry.shown = [field](const Options& o) { return std::to_string(o.*field); };
    entry.yaml = entry.shown;
    return *this;
  }

  OptionTable& Real(const char* name, double Options::*field, const Bounds& bounds,
                    const char* doc) {
    Entry& entry = Add(name, "real", bounds.Text(false), doc);
    entry.read = [key = entry.key, field](const SettingsFile& file, Options& o) {
      o.*field = file.GetDouble(key, o.*field);
    };
    entry.ok = [field, bounds](const Options& o) { return bounds.Contains(o.*field); };
    entry.rule = bounds.Rule(false);
    entry.shown = [field](const Options& o) { return option_format::ShownReal(o.*field); };
    entry.yaml = [field](const Options& o) { return option_format::YamlReal(o.*field); };
    return *this;
  }

  OptionTable& Text(const char* name, std::string Options::*field, const char* doc) {
    return AddText(name, "text", field, doc, false);
  }

  // A file name; a relative one is taken relative to the settings file's folder.
  OptionTable& Path(const char* name, std::string Options::*field, const char* doc) {
    return AddText(name, "path", field, doc, true);
  }

  // A sequence of strings ([a, b]) or one comma-separated string.
  OptionTable& List(const char* name, std::vector<std::string> Options::*field, const char* doc) {
    Entry& entry = Add(name, "list", "", doc);
    entry.read = [key = entry.key, field](const SettingsFile& file, Options& o) {
      o.*field = file.GetStringList(key, o.*field);
    };
    entry.shown = [field](const Options& o) { return option_format::ShownList(o.*field); };
    entry.yaml = [field](const Options& o) { return option_format::YamlList(o.*field); };
    return *this;
  }

  template <typename Enum>
  OptionTable& Choice(const char* name, Enum Options::*field, const Choices<Enum>& choices,
                      const char* doc) {
    std::vector<std::string> names;
    for (const auto& choice : choices) names.push_back(choice.first);
    Entry& entry = Add(name, "choice", option_format::Join(names, " | "), doc);
    entry.read = [key = entry.key, field, choices](const SettingsFile& file, Options& o) {
      o.*field = ParseChoice(file.GetString(key, ChoiceName(o.*field, choices)), key, choices);
    };
    entry.shown = [field, choices](const Options& o) { return ChoiceName(o.*field, choices); };
    entry.yaml = [field, choices](const Options& o) {
      return option_format::YamlText(ChoiceName(o.*field, choices));
    };
    return *this;
  }

  // A rule beyond the key's own bounds (between keys, or on text), checked after every key's
  // bounds in declaration order; when `ok` fails: Error("<key> = <value> <rule>").
  OptionTable& Rule(const char* name, std::function<bool(const Options&)> ok, std::string rule) {
    const std::string key = Key(name);
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (entries_[i].key != key) continue;
      Entry& entry = entries_[i];
      entry.allowed += (entry.allowed.empty() ? "" : "; ") + rule;
      rules_.push_back({i, std::move(ok), std::move(rule)});
      return *this;
    }
    throw Error("OptionTable: rule for undeclared key " + key);
  }

  // Defaults, then every key present in `file`, then Check(). Errors name the file and the key.
  Options Load(const SettingsFile& file) const {
    Options options;
    try {
      for (const Entry& entry : entries_) entry.read(file, options);
      Check(options);
    } catch (const Error& e) {
      const std::string message = e.what();
      if (message.rfind(file.Path(), 0) == 0) throw;
      throw Error(file.Path() + ": " + message);
    }
    return options;
  }

  // Throws Error("<key> = <value> <rule>") for the first key out of bounds, then the first
  // broken rule.
  void Check(const Options& options) const {
    for (const Entry& entry : entries_) {
      if (entry.ok && !entry.ok(options)) Fail(entry, options, entry.rule);
    }
    for (const Constraint& rule : rules_) {
      if (!rule.ok(options)) Fail(entries_[rule.entry], options, rule.rule);
    }
  }

  // The section as docs and dumps show it, defaults from a default-constructed Options.
  OptionSection Describe() const {
    const Options defaults;
    OptionSection section{section_, summary_, {}};
    for (const Entry& entry : entries_) {
      section.options.push_back(
          {entry.key, entry.type, entry.yaml(defaults), entry.allowed, entry.doc});
    }
    return section;
  }

  // "Key: value" lines, one per key in declaration order, that load back to `options`.
  std::string Yaml(const Options& options) const {
    std::string text;
    for (const Entry& entry : entries_) text += entry.key + ": " + entry.yaml(options) + "\n";
    return text;
  }

  // Keys whose values differ between `a` and `b` (reals compared by their exact text).
  std::vector<std::string> Differences(const Options& a, const Options& b) const {
    std::vector<std::string> keys;
    for (const Entry& entry : entries_) {
      if (entry.yaml(a) != entry.yaml(b)) keys.push_back(entry.key);
    }
    return keys;
  }

 private:
  struct Entry {
    std::string key, type, allowed, doc;
    std::function<void(const SettingsFile&, Options&)> read;
    std::function<bool(const Options&)> ok;  // the bounds; empty: any value of the type
    std::string rule;
    std::function<std::string(const Options&)> shown;  // the value in error messages
    std::function<std::string(const Options&)> yaml;   // the value in a settings file
  };
  struct Constraint {
    std::size_t entry;
    std::function<bool(const Options&)> ok;
    std::string rule;
  };

  std::string Key(const char* name) const {
    return section_.empty() ? std::string(name) : section_ + "." + name;
  }

  Entry& Add(const char* name, const char* type, std::string allowed, const char* doc) {
    Entry entry;
    entry.key = Key(name);
    entry.type = type;
    entry.allowed = std::move(allowed);
    entry.doc = doc;
    entries_.push_back(std::move(entry));
    return entries_.back();
  }

  OptionTable& AddText(const char* name, const char* type, std::string Options::*field,
                       const char* doc, bool path) {
    Entry& entry = Add(name, type, "", doc);
    entry.read = [key = entry.key, field, path](const SettingsFile& file, Options& o) {
      o.*field = file.GetString(key, o.*field);
      if (path) o.*field = option_format::BesideFile(o.*field, file.Path());
    };
    entry.shown = [field](const Options& o) { return "'" + o.*field + "'"; };
    entry.yaml = [field](const Options& o) { return option_format::YamlText(o.*field); };
    return *this;
  }

  [[noreturn]] static void Fail(const Entry& entry, const Options& options,
                                const std::string& rule) {
    throw Error(entry.key + " = " + entry.shown(options) + " " + rule);
  }

  std::string section_;
  std::string summary_;
  std::vector<Entry> entries_;
  std::vector<Constraint> rules_;
};

}  // namespace drvslam
