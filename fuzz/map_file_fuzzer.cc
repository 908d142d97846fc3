// libFuzzer target of the map_file body (fuzz/fuzz_bodies/fuzz_bodies.h); scripts/fuzz.sh runs it.
#include "fuzzer_entry.h"

DRVSLAM_FUZZER(RunMapFileBody)
