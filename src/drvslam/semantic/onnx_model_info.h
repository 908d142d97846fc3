// OnnxModelInfo: the few facts about an ONNX file that OpenCV DNN does not expose: the input
// tensor's shape (to letterbox to the model's own size) and the metadata_props strings (where
// Ultralytics stores the class names). Read with a minimal protobuf wire-format parser, so no
// ONNX or protobuf library is needed.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace drvslam {

struct OnnxModelInfo {
  std::int64_t ir_version = 0;
  std::string producer_name;
  // The first graph input that is not an initializer (the image tensor).
  std::string input_name;
  // Its dimensions, -1 for symbolic (dynamic) ones; empty when the file does not say.
  std::vector<std::int64_t> input_shape;
  std::vector<std::string> output_names;
  std::map<std::string, std::string> metadata;
};

// Throws drvslam::Error naming `path` when it is missing, unreadable, or not an ONNX model.
OnnxModelInfo ReadOnnxModelInfo(const std::string& path);
// The same from the bytes of a model; `source` names them in errors.
OnnxModelInfo ParseOnnxModelInfo(const std::string& bytes, const std::string& source);

// Class names from an Ultralytics "names" metadata value, a Python dict literal such as
// "{0: 'person', 1: 'bicycle'}" (JSON-style {"0": "person"} too). Returns an empty list when the
// text is not such a dict or its ids are not 0..n-1.
std::vector<std::string> ParseClassNamesMetadata(const std::string& text);

}  // namespace drvslam
