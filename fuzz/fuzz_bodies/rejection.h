// The one outcome besides success that a parser of outside input may have: a drvslam::Error.
#pragma once

#include "drvslam/core/error.h"

namespace drvslam::fuzz {

// Runs `parse`; a drvslam::Error (the parser rejecting its input) ends it quietly. Anything
// else (another exception, a crash) goes on to the fuzzer or the test.
template <typename Parse>
void AllowRejection(const Parse& parse) {
  try {
    parse();
  } catch (const Error&) {
  }
}

}  // namespace drvslam::fuzz
