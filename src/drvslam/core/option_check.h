// RequireOption: the one way options structs' Check() report a bad value, so every message reads
// "<key> = <value> <rule>"; CheckedOptions adds the settings file's name when loading.
#pragma once

#include <sstream>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {

template <typename T>
void RequireOption(bool ok, const std::string& key, const T& value, const std::string& rule) {
  if (ok) return;
  std::ostringstream message;
  message << key << " = " << value << " " << rule;
  throw Error(message.str());
}

// Runs options.Check() on options loaded from the settings file at `path` and returns them; a
// failure's message is prefixed with the path.
template <typename Options>
Options CheckedOptions(const std::string& path, Options options) {
  try {
    options.Check();
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return options;
}

}  // namespace drvslam
