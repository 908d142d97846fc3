// ErrorMessageOf: what a drvslam::Error thrown by an action says, for tests whose contract is the
// message (the file, key or value it names), without a try / FAIL / catch around every call.
#pragma once

#include <string>

#include "drvslam/core/error.h"

namespace drvslam::testing {

// The message of the drvslam::Error that `action` throws; empty when it throws none, so that a
// check of what the message says fails then too.
template <typename Action>
std::string ErrorMessageOf(Action&& action) {
  std::string message;
  try {
    action();
  } catch (const Error& error) {
    message = error.what();
  }
  return message;
}

}  // namespace drvslam::testing
