// What the YOLO segmenter reads of a model file besides the network (OpenCV DNN parses that):
// the input shape and the metadata, with the class names in Ultralytics' "names" entry.
#include <string>

#include "drvslam/semantic/onnx_model_info.h"
#include "fuzz_bodies/fuzz_bodies.h"
#include "fuzz_bodies/rejection.h"

namespace drvslam::fuzz {

void RunOnnxMetadataBody(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const std::string rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 1) {
    ParseClassNamesMetadata(rest);
    return;
  }
  AllowRejection([&] {
    const OnnxModelInfo info = ParseOnnxModelInfo(rest, "fuzz.onnx");
    const auto names = info.metadata.find("names");
    if (names != info.metadata.end()) ParseClassNamesMetadata(names->second);
  });
}

}  // namespace drvslam::fuzz
