// RequireOption: the one way options structs' Check() report a bad value, so every message reads
// "<key> = <value> <rule>" (callers add the file name).
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

}  // namespace drvslam
