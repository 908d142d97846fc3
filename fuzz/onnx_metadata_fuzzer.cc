// libFuzzer target of the onnx_metadata body (fuzz/fuzz_bodies/fuzz_bodies.h); scripts/fuzz.sh runs
// it.
#include "fuzzer_entry.h"

DRVSLAM_FUZZER(RunOnnxMetadataBody)
