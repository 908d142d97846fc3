// FrameError: a drvslam::Error for one frame of a sequence that cannot be used (a missing,
// empty, corrupt, wrongly sized or wrongly typed image, or a list entry whose timestamp does not
// increase). It carries the fault's kind and the file, so a run can skip the frame and count it
// instead of stopping; a caller that does not care still sees an Error naming the file.
#pragma once

#include <string>

#include "drvslam/core/error.h"

namespace drvslam {

enum class FrameFault {
  kMissingFile,             // listed image does not exist (real Bonn sequences miss some)
  kEmptyFile,               // 0-byte image file
  kCorruptImage,            // cannot be decoded (corrupt or truncated)
  kWrongSize,               // not the camera's (or the first frame's) size
  kWrongType,               // bit depth or channel count the pipeline cannot use
  kTimestampNotIncreasing,  // list entry repeats or goes back in time
};

// The stats.json name of a fault, e.g. "corrupt_image".
const char* FrameFaultName(FrameFault fault);

class FrameError : public Error {
 public:
  FrameError(FrameFault fault, const std::string& path, const std::string& message)
      : Error(message), fault_(fault), path_(path) {}

  FrameFault Fault() const { return fault_; }
  const std::string& Path() const { return path_; }

 private:
  FrameFault fault_;
  std::string path_;
};

}  // namespace drvslam
