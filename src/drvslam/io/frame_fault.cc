#include "drvslam/io/frame_fault.h"

namespace drvslam {

const char* FrameFaultName(FrameFault fault) {
  switch (fault) {
    case FrameFault::kMissingFile:
      return "missing_file";
    case FrameFault::kEmptyFile:
      return "empty_file";
    case FrameFault::kCorruptImage:
      return "corrupt_image";
    case FrameFault::kWrongSize:
      return "wrong_size";
    case FrameFault::kWrongType:
      return "wrong_type";
    case FrameFault::kTimestampNotIncreasing:
      return "timestamp_not_increasing";
  }
  return "unknown";
}

}  // namespace drvslam
