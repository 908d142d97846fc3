#include "drvslam/semantic/onnx_model_info.h"

#include <cctype>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

// Protobuf wire types used by ONNX (groups, types 3 and 4, are obsolete and never written).
constexpr int kVarint = 0;
constexpr int kFixed64 = 1;
constexpr int kLengthDelimited = 2;
constexpr int kFixed32 = 5;

struct Malformed {
  std::size_t offset;
  const char* what;
};

struct Field {
  std::uint32_t number = 0;
  int wire_type = 0;
  std::uint64_t varint = 0;
  std::string_view bytes;
};

// Walks the fields of one message; `base` is the message's offset in the file, for errors.
class WireReader {
 public:
  WireReader(std::string_view message, std::size_t base) : data_(message), base_(base) {}

  bool Next(Field& field) {
    if (pos_ >= data_.size()) return false;
    const std::uint64_t tag = ReadVarint();
    field.number = static_cast<std::uint32_t>(tag >> 3);
    field.wire_type = static_cast<int>(tag & 7);
    if (field.number == 0 || (tag >> 3) > 0x1fffffff) Fail("invalid field number");
    switch (field.wire_type) {
      case kVarint:
        field.varint = ReadVarint();
        break;
      case kFixed64:
        Skip(8);
        break;
      case kFixed32:
        Skip(4);
        break;
      case kLengthDelimited: {
        const std::uint64_t length = ReadVarint();
        if (length > data_.size() - pos_) Fail("length runs past the end");
        field.bytes = data_.substr(pos_, static_cast<std::size_t>(length));
        pos_ += static_cast<std::size_t>(length);
        break;
      }
      default:
        Fail("unknown wire type");
    }
    return true;
  }

  // Offset in the file of the bytes of a length-delimited field just read.
  std::size_t OffsetOf(const Field& field) const {
    return base_ + static_cast<std::size_t>(field.bytes.data() - data_.data());
  }

 private:
  std::uint64_t ReadVarint() {
    std::uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (pos_ >= data_.size()) Fail("truncated varint");
      const auto byte = static_cast<unsigned char>(data_[pos_++]);
      value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    Fail("varint longer than 10 bytes");
    return 0;
  }
  void Skip(std::size_t count) {
    if (count > data_.size() - pos_) Fail("truncated fixed-size field");
    pos_ += count;
  }
  [[noreturn]] void Fail(const char* what) const { throw Malformed{base_ + pos_, what}; }

  std::string_view data_;
  std::size_t base_;
  std::size_t pos_ = 0;
};

// Each Parse* takes one sub-message and its offset in the file.
std::string ParseName(std::string_view message, std::size_t base, std::uint32_t name_field) {
  WireReader reader(message, base);
  Field field;
  std::string name;
  while (reader.Next(field)) {
    if (field.number == name_field && field.wire_type == kLengthDelimited) {
      name = std::string(field.bytes);
    }
  }
  return name;
}

std::vector<std::int64_t> ParseShape(std::string_view shape, std::size_t base) {
  std::vector<std::int64_t> dims;
  WireReader reader(shape, base);
  Field dim;
  while (reader.Next(dim)) {
    if (dim.number != 1 || dim.wire_type != kLengthDelimited) continue;
    std::int64_t value = -1;
    WireReader dim_reader(dim.bytes, reader.OffsetOf(dim));
    Field part;
    while (dim_reader.Next(part)) {
      if (part.number == 1 && part.wire_type == kVarint) {
        value = static_cast<std::int64_t>(part.varint);
      }
    }
    dims.push_back(value > 0 ? value : -1);
  }
  return dims;
}

// ValueInfoProto {1 name, 2 TypeProto {1 tensor_type {1 elem_type, 2 shape}}}.
void ParseValueInfo(std::string_view message, std::size_t base, std::string& name,
                    std::vector<std::int64_t>& shape) {
  WireReader reader(message, base);
  Field field;
  while (reader.Next(field)) {
    if (field.wire_type != kLengthDelimited) continue;
    if (field.number == 1) {
      name = std::string(field.bytes);
    } else if (field.number == 2) {
      WireReader type_reader(field.bytes, reader.OffsetOf(field));
      Field type_field;
      while (type_reader.Next(type_field)) {
        if (type_field.number != 1 || type_field.wire_type != kLengthDelimited) continue;
        WireReader tensor_reader(type_field.bytes, type_reader.OffsetOf(type_field));
        Field tensor_field;
        while (tensor_reader.Next(tensor_field)) {
          if (tensor_field.number == 2 && tensor_field.wire_type == kLengthDelimited) {
            shape = ParseShape(tensor_field.bytes, tensor_reader.OffsetOf(tensor_field));
          }
        }
      }
    }
  }
}

// GraphProto {5 initializer (TensorProto, 8 name), 11 input, 12 output}.
void ParseGraph(std::string_view graph, std::size_t base, OnnxModelInfo& info) {
  std::set<std::string> initializers;
  struct Input {
    std::string name;
    std::vector<std::int64_t> shape;
  };
  std::vector<Input> inputs;
  WireReader reader(graph, base);
  Field field;
  while (reader.Next(field)) {
    if (field.wire_type != kLengthDelimited) continue;
    if (field.number == 5) {
      initializers.insert(ParseName(field.bytes, reader.OffsetOf(field), 8));
    } else if (field.number == 11) {
      Input input;
      ParseValueInfo(field.bytes, reader.OffsetOf(field), input.name, input.shape);
      inputs.push_back(std::move(input));
    } else if (field.number == 12) {
      std::string name;
      std::vector<std::int64_t> unused_shape;
      ParseValueInfo(field.bytes, reader.OffsetOf(field), name, unused_shape);
      info.output_names.push_back(name);
    }
  }
  // Before IR version 4 initializers were also listed as inputs.
  for (const Input& input : inputs) {
    if (initializers.count(input.name) == 0) {
      info.input_name = input.name;
      info.input_shape = input.shape;
      return;
    }
  }
}

std::string FormatMalformed(const std::string& source, const Malformed& m) {
  std::ostringstream message;
  message << source << ": not an ONNX model (" << m.what << " at byte " << m.offset << ")";
  return message.str();
}

}  // namespace

OnnxModelInfo ParseOnnxModelInfo(const std::string& bytes, const std::string& source) {
  OnnxModelInfo info;
  bool has_graph = false;
  bool has_ir_version = false;
  try {
    // ModelProto {1 ir_version, 2 producer_name, 7 graph, 14 metadata_props {1 key, 2 value}}.
    WireReader reader(bytes, 0);
    Field field;
    while (reader.Next(field)) {
      if (field.number == 1 && field.wire_type == kVarint) {
        info.ir_version = static_cast<std::int64_t>(field.varint);
        has_ir_version = true;
      } else if (field.wire_type != kLengthDelimited) {
        continue;
      } else if (field.number == 2) {
        info.producer_name = std::string(field.bytes);
      } else if (field.number == 7) {
        ParseGraph(field.bytes, reader.OffsetOf(field), info);
        has_graph = true;
      } else if (field.number == 14) {
        WireReader entry(field.bytes, reader.OffsetOf(field));
        Field part;
        std::string key;
        std::string value;
        while (entry.Next(part)) {
          if (part.wire_type != kLengthDelimited) continue;
          if (part.number == 1) key = std::string(part.bytes);
          if (part.number == 2) value = std::string(part.bytes);
        }
        info.metadata[key] = value;
      }
    }
  } catch (const Malformed& m) {
    throw Error(FormatMalformed(source, m));
  }
  if (!has_ir_version || !has_graph) {
    throw Error(source + ": not an ONNX model (no " + (has_graph ? "ir_version" : "graph") + ")");
  }
  if (info.input_name.empty()) throw Error(source + ": ONNX graph has no input tensor");
  return info;
}

OnnxModelInfo ReadOnnxModelInfo(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": model file does not exist");
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": model path is a folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the model file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw Error(path + ": cannot read the model file");
  return ParseOnnxModelInfo(bytes.str(), path);
}

std::vector<std::string> ParseClassNamesMetadata(const std::string& text) {
  std::vector<std::string> names;
  std::vector<bool> seen;
  std::size_t pos = 0;
  const auto skip_space = [&] {
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
  };
  const auto expect = [&](char c) {
    skip_space();
    if (pos < text.size() && text[pos] == c) {
      ++pos;
      return true;
    }
    return false;
  };
  // A quoted string with either quote; backslash escapes the next character.
  const auto read_quoted = [&](std::string& out) {
    skip_space();
    if (pos >= text.size() || (text[pos] != '\'' && text[pos] != '"')) return false;
    const char quote = text[pos++];
    out.clear();
    while (pos < text.size() && text[pos] != quote) {
      if (text[pos] == '\\' && pos + 1 < text.size()) ++pos;
      out.push_back(text[pos++]);
    }
    if (pos >= text.size()) return false;
    ++pos;
    return true;
  };
  const auto read_index = [&](long& out) {
    skip_space();
    const bool quoted = pos < text.size() && (text[pos] == '\'' || text[pos] == '"');
    const char quote = quoted ? text[pos++] : 0;
    const std::size_t start = pos;
    while (pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos]))) ++pos;
    if (pos == start || pos - start > 6) return false;
    out = std::stol(text.substr(start, pos - start));
    if (quoted) {
      if (pos >= text.size() || text[pos] != quote) return false;
      ++pos;
    }
    return true;
  };

  if (!expect('{')) return {};
  if (expect('}')) return {};
  while (true) {
    long index = 0;
    std::string name;
    if (!read_index(index) || !expect(':') || !read_quoted(name)) return {};
    if (static_cast<std::size_t>(index) >= names.size()) {
      names.resize(index + 1);
      seen.resize(index + 1, false);
    }
    if (seen[index]) return {};
    names[index] = name;
    seen[index] = true;
    if (expect('}')) break;
    if (!expect(',')) return {};
  }
  skip_space();
  if (pos != text.size()) return {};
  for (bool present : seen) {
    if (!present) return {};
  }
  return names;
}

}  // namespace drvslam
