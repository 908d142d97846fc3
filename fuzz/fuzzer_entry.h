// The libFuzzer entry points of one fuzz body: DRVSLAM_FUZZER(RunMapFileBody) in
// fuzz/map_file_fuzzer.cc makes map_file_fuzzer. Logging is off (fuzz_bodies.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzz_bodies/fuzz_bodies.h"

#define DRVSLAM_FUZZER(body)                                                          \
  extern "C" int LLVMFuzzerInitialize(int*, char***) {                                \
    drvslam::fuzz::SilenceLogging();                                                  \
    return 0;                                                                         \
  }                                                                                   \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    drvslam::fuzz::body(data, size);                                                  \
    return 0;                                                                         \
  }
