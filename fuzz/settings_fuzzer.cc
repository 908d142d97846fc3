// libFuzzer target of the settings body (fuzz/fuzz_bodies/fuzz_bodies.h); scripts/fuzz.sh runs it.
#include "fuzzer_entry.h"

DRVSLAM_FUZZER(RunSettingsBody)
