// A few lines of protobuf encoding, enough to write tiny ONNX files in tests: models with a
// chosen input shape, metadata, and outputs that are not a YOLO layout.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace drvslam::testing {

inline std::string Varint(std::uint64_t value) {
  std::string out;
  do {
    unsigned char byte = value & 0x7f;
    value >>= 7;
    if (value != 0) byte |= 0x80;
    out.push_back(static_cast<char>(byte));
  } while (value != 0);
  return out;
}

inline std::string VarintField(int number, std::uint64_t value) {
  return Varint(static_cast<std::uint64_t>(number) << 3) + Varint(value);
}

inline std::string BytesField(int number, const std::string& bytes) {
  return Varint((static_cast<std::uint64_t>(number) << 3) | 2) + Varint(bytes.size()) + bytes;
}

// ValueInfoProto of a float tensor; negative dims become symbolic ("batch").
inline std::string TensorInfo(const std::string& name, const std::vector<std::int64_t>& dims) {
  std::string shape;
  for (std::int64_t d : dims) {
    shape += BytesField(
        1, d >= 0 ? VarintField(1, static_cast<std::uint64_t>(d)) : BytesField(2, "batch"));
  }
  const std::string tensor_type = VarintField(1, 1) + BytesField(2, shape);
  return BytesField(1, name) + BytesField(2, BytesField(1, tensor_type));
}

inline std::string Node(const std::string& op, const std::string& input,
                        const std::string& output) {
  return BytesField(1, input) + BytesField(2, output) + BytesField(3, output + "_node") +
         BytesField(4, op);
}

struct TinyModel {
  std::vector<std::int64_t> input_dims = {1, 3, 64, 64};
  // One Relu node per output, each reading the image.
  std::vector<std::string> outputs = {"output0"};
  std::vector<std::pair<std::string, std::string>> metadata;
  bool with_initializer = false;

  std::string Bytes() const {
    std::string graph;
    for (const std::string& output : outputs)
      graph += BytesField(1, Node("Relu", "images", output));
    graph += BytesField(2, "tiny");
    if (with_initializer) {
      // An initializer also listed as an input, as IR version 3 files do.
      graph += BytesField(5, VarintField(1, 1) + VarintField(2, 1) + BytesField(8, "weights"));
      graph += BytesField(11, TensorInfo("weights", {1}));
    }
    graph += BytesField(11, TensorInfo("images", input_dims));
    for (const std::string& output : outputs) graph += BytesField(12, TensorInfo(output, {}));
    std::string model = VarintField(1, 7) + BytesField(2, "drvslam-test") + BytesField(7, graph) +
                        BytesField(8, BytesField(1, "") + VarintField(2, 13));
    for (const auto& [key, value] : metadata) {
      model += BytesField(14, BytesField(1, key) + BytesField(2, value));
    }
    return model;
  }
};

}  // namespace drvslam::testing
