#include "drvslam/io/frame_fault.h"

#include "drvslam/core/enum_names.h"

namespace drvslam {

const char* FrameFaultName(FrameFault fault) {
  static constexpr EnumName<FrameFault> kNames[] = {
      {FrameFault::kMissingFile, "missing_file"},
      {FrameFault::kEmptyFile, "empty_file"},
      {FrameFault::kCorruptImage, "corrupt_image"},
      {FrameFault::kWrongSize, "wrong_size"},
      {FrameFault::kWrongType, "wrong_type"},
      {FrameFault::kTimestampNotIncreasing, "timestamp_not_increasing"}};
  return NameOf(fault, kNames, "unknown");
}

}  // namespace drvslam
