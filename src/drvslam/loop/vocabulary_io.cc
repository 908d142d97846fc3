#include "drvslam/loop/vocabulary_io.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string_view>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/loop/vocabulary_builder.h"

namespace drvslam {
namespace {

constexpr char kBinaryMagic[8] = {'D', 'R', 'V', 'S', 'B', 'O', 'W', '\0'};
constexpr uint32_t kBinaryVersion = 1;
constexpr std::size_t kBinaryHeaderBytes = 36;
constexpr std::size_t kBinaryNodeBytes = 4 + 1 + 32 + 8;
constexpr int kFileDescriptorBytes = 32;
// parent, is_leaf, 32 bytes, weight.
constexpr int kTextNodeFields = 2 + kFileDescriptorBytes + 1;

std::string ReadWholeFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot open vocabulary file");
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  if (size < 0) throw Error(path + ": cannot read vocabulary file");
  file.seekg(0, std::ios::beg);
  std::string content(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !file.read(content.data(), size)) {
    throw Error(path + ": cannot read vocabulary file");
  }
  return content;
}

// ---- text ----

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Splits on blanks; stops after max_fields + 1 so a long line is not split in full just to say
// it has too many fields.
int SplitFields(std::string_view line, std::string_view* fields, int max_fields) {
  int count = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    if (i == line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    if (count == max_fields) return count + 1;
    fields[count++] = line.substr(start, i - start);
  }
  return count;
}

std::string Quote(std::string_view text) {
  constexpr std::size_t kMaxShown = 60;
  if (text.size() > kMaxShown) return "'" + std::string(text.substr(0, kMaxShown)) + "...'";
  return "'" + std::string(text) + "'";
}

bool ParseInt(std::string_view field, long long* value) {
  const char* end = field.data() + field.size();
  const auto result = std::from_chars(field.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

bool ParseDouble(std::string_view field, double* value) {
  const char* end = field.data() + field.size();
  const auto result = std::from_chars(field.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

class TextLineError {
 public:
  TextLineError(const std::string& path, long long line) : path_(path), line_(line) {}
  [[noreturn]] void operator()(const std::string& problem) const {
    throw Error(path_ + ": line " + std::to_string(line_) + ": " + problem);
  }

 private:
  const std::string& path_;
  long long line_;
};

// ---- binary ----

uint32_t GetU32(const unsigned char* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
         static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

uint64_t GetU64(const unsigned char* p) {
  return static_cast<uint64_t>(GetU32(p)) | static_cast<uint64_t>(GetU32(p + 4)) << 32;
}

void PutU32(uint32_t value, std::string* out) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}

void PutU64(uint64_t value, std::string* out) {
  PutU32(static_cast<uint32_t>(value), out);
  PutU32(static_cast<uint32_t>(value >> 32), out);
}

[[noreturn]] void BinaryFail(const std::string& path, std::size_t offset,
                             const std::string& problem) {
  throw Error(path + ": offset " + std::to_string(offset) + ": " + problem);
}

void WriteAll(const std::string& path, std::ofstream* file, const std::string& chunk) {
  if (!file->write(chunk.data(), static_cast<std::streamsize>(chunk.size()))) {
    throw Error(path + ": cannot write vocabulary file");
  }
}

std::ofstream OpenForWriting(const BowVocabulary& vocabulary, const std::string& path) {
  if (vocabulary.Empty()) throw Error(path + ": cannot write an empty vocabulary");
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw Error(path + ": cannot open vocabulary file for writing");
  return file;
}

void CloseAfterWriting(const std::string& path, std::ofstream* file) {
  file->close();
  if (!*file) throw Error(path + ": cannot write vocabulary file");
}

}  // namespace

VocabularyFormat ParseVocabularyFormat(const std::string& name) {
  if (name == "text") return VocabularyFormat::kText;
  if (name == "binary") return VocabularyFormat::kBinary;
  throw Error("vocabulary format '" + name + "' unknown (expected text or binary)");
}

const char* VocabularyFormatName(VocabularyFormat format) {
  return format == VocabularyFormat::kText ? "text" : "binary";
}

BowVocabulary ReadTextVocabulary(const std::string& path) {
  const std::string content = ReadWholeFile(path);
  const std::string_view text(content);
  std::size_t line_start = 0;
  long long line_number = 0;
  // The next line, without its '\n'; false at the end of the text.
  auto next_line = [&](std::string_view* line) {
    if (line_start >= text.size()) return false;
    std::size_t end = text.find('\n', line_start);
    if (end == std::string_view::npos) end = text.size();
    *line = text.substr(line_start, end - line_start);
    line_start = end + 1;
    ++line_number;
    return true;
  };

  std::string_view line;
  std::array<std::string_view, kTextNodeFields + 1> fields;
  if (!next_line(&line)) {
    throw Error(path + ": line 1: missing header 'k L scoring weighting' (empty file)");
  }
  long long header[4];
  if (SplitFields(line, fields.data(), 4) != 4 || !ParseInt(fields[0], &header[0]) ||
      !ParseInt(fields[1], &header[1]) || !ParseInt(fields[2], &header[2]) ||
      !ParseInt(fields[3], &header[3])) {
    TextLineError(path,
                  1)("header must be 'k L scoring weighting' (4 integers), found " + Quote(line));
  }
  if (header[2] != BowVocabulary::kL1Scoring) {
    TextLineError(path, 1)("unsupported scoring type " + std::to_string(header[2]) +
                           " (only 0, the L1 norm, is supported)");
  }
  if (header[3] != BowVocabulary::kTfIdfWeighting) {
    TextLineError(path, 1)("unsupported weighting type " + std::to_string(header[3]) +
                           " (only 0, TF-IDF, is supported)");
  }
  const auto clamp_int = [](long long value) {
    return static_cast<int>(std::clamp<long long>(value, INT_MIN, INT_MAX));
  };
  VocabularyBuilder builder(clamp_int(header[0]), clamp_int(header[1]), path, "line 1");
  builder.Reserve(static_cast<std::size_t>(std::count(content.begin(), content.end(), '\n')) + 1);

  uint8_t descriptor[kFileDescriptorBytes];
  while (next_line(&line)) {
    const int count = SplitFields(line, fields.data(), kTextNodeFields);
    if (count == 0) continue;
    const TextLineError fail(path, line_number);
    if (count != kTextNodeFields) {
      fail("expected " + std::to_string(kTextNodeFields) +
           " fields (parent_id is_leaf d0 ... d31 weight), found " +
           (count > kTextNodeFields ? "more" : std::to_string(count)));
    }
    long long parent = 0;
    if (!ParseInt(fields[0], &parent)) fail("parent id " + Quote(fields[0]) + " is not an integer");
    long long is_leaf = 0;
    if (!ParseInt(fields[1], &is_leaf) || (is_leaf != 0 && is_leaf != 1)) {
      fail("is_leaf " + Quote(fields[1]) + " must be 0 or 1");
    }
    for (int b = 0; b < kFileDescriptorBytes; ++b) {
      long long value = 0;
      if (!ParseInt(fields[2 + b], &value) || value < 0 || value > 255) {
        fail("descriptor byte d" + std::to_string(b) + " " + Quote(fields[2 + b]) +
             " is not an integer in [0, 255]");
      }
      descriptor[b] = static_cast<uint8_t>(value);
    }
    double weight = 0.0;
    if (!ParseDouble(fields[kTextNodeFields - 1], &weight)) {
      fail("weight " + Quote(fields[kTextNodeFields - 1]) + " is not a number");
    }
    builder.AddNode(clamp_int(parent), is_leaf == 1, descriptor, weight, "line", line_number);
  }
  return builder.Finish();
}

BowVocabulary ReadBinaryVocabulary(const std::string& path) {
  const std::string content = ReadWholeFile(path);
  const auto* data = reinterpret_cast<const unsigned char*>(content.data());
  const std::size_t size = content.size();
  if (size < sizeof(kBinaryMagic) || std::memcmp(data, kBinaryMagic, sizeof(kBinaryMagic)) != 0) {
    BinaryFail(path, 0, "not a drvslam binary vocabulary (bad magic)");
  }
  if (size < kBinaryHeaderBytes) {
    BinaryFail(path, size,
               "truncated header (" + std::to_string(size) + " bytes, expected " +
                   std::to_string(kBinaryHeaderBytes) + ")");
  }
  const uint32_t version = GetU32(data + 8);
  if (version != kBinaryVersion) {
    BinaryFail(path, 8,
               "unsupported binary vocabulary version " + std::to_string(version) +
                   " (this build reads version " + std::to_string(kBinaryVersion) + ")");
  }
  const uint32_t k = GetU32(data + 12);
  const uint32_t levels = GetU32(data + 16);
  const uint32_t scoring = GetU32(data + 20);
  const uint32_t weighting = GetU32(data + 24);
  const uint64_t node_count = GetU64(data + 28);
  if (scoring != BowVocabulary::kL1Scoring) {
    BinaryFail(path, 20,
               "unsupported scoring type " + std::to_string(scoring) +
                   " (only 0, the L1 norm, is supported)");
  }
  if (weighting != BowVocabulary::kTfIdfWeighting) {
    BinaryFail(path, 24,
               "unsupported weighting type " + std::to_string(weighting) +
                   " (only 0, TF-IDF, is supported)");
  }
  VocabularyBuilder builder(static_cast<int>(std::min<uint32_t>(k, INT_MAX)),
                            static_cast<int>(std::min<uint32_t>(levels, INT_MAX)), path,
                            "offset 12");
  const std::size_t body = size - kBinaryHeaderBytes;
  if (node_count > body / kBinaryNodeBytes) {
    BinaryFail(path, size,
               "truncated: the header promises " + std::to_string(node_count) +
                   " nodes but the file ends after " + std::to_string(body / kBinaryNodeBytes) +
                   " complete ones");
  }
  if (node_count * kBinaryNodeBytes != body) {
    const std::size_t end = kBinaryHeaderBytes + node_count * kBinaryNodeBytes;
    BinaryFail(path, end,
               std::to_string(size - end) + " unexpected bytes after the last of " +
                   std::to_string(node_count) + " nodes");
  }
  builder.Reserve(static_cast<std::size_t>(node_count) + 1);
  for (uint64_t i = 0; i < node_count; ++i) {
    const std::size_t offset = kBinaryHeaderBytes + i * kBinaryNodeBytes;
    const unsigned char* record = data + offset;
    const uint32_t parent = GetU32(record);
    const unsigned char is_leaf = record[4];
    if (parent > static_cast<uint32_t>(INT_MAX)) {
      BinaryFail(path, offset,
                 "parent id " + std::to_string(parent) + " of node " + std::to_string(i + 1) +
                     " out of range");
    }
    if (is_leaf > 1) {
      BinaryFail(path, offset + 4, "is_leaf byte " + std::to_string(is_leaf) + " must be 0 or 1");
    }
    double weight = 0.0;
    const uint64_t weight_bits = GetU64(record + 5 + kFileDescriptorBytes);
    std::memcpy(&weight, &weight_bits, sizeof(weight));
    builder.AddNode(static_cast<int>(parent), is_leaf == 1, record + 5, weight, "offset",
                    static_cast<int64_t>(offset));
  }
  return builder.Finish();
}

VocabularyFormat DetectVocabularyFormat(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot open vocabulary file");
  char magic[sizeof(kBinaryMagic)] = {};
  file.read(magic, sizeof(magic));
  const bool binary = file.gcount() == static_cast<std::streamsize>(sizeof(magic)) &&
                      std::memcmp(magic, kBinaryMagic, sizeof(magic)) == 0;
  return binary ? VocabularyFormat::kBinary : VocabularyFormat::kText;
}

BowVocabulary LoadVocabulary(const std::string& path) {
  return DetectVocabularyFormat(path) == VocabularyFormat::kBinary ? ReadBinaryVocabulary(path)
                                                                   : ReadTextVocabulary(path);
}

void WriteTextVocabulary(const BowVocabulary& vocabulary, const std::string& path) {
  std::ofstream file = OpenForWriting(vocabulary, path);
  std::string chunk = std::to_string(vocabulary.BranchingFactor()) + " " +
                      std::to_string(vocabulary.Depth()) + " " +
                      std::to_string(BowVocabulary::kL1Scoring) + " " +
                      std::to_string(BowVocabulary::kTfIdfWeighting) + "\n";
  constexpr std::size_t kChunkBytes = 1 << 20;
  char number[64];
  const auto append_number = [&](auto value) {
    const auto result = std::to_chars(number, number + sizeof(number), value);
    chunk.append(number, result.ptr);
  };
  const int node_count = static_cast<int>(vocabulary.NodeCount());
  for (int node = 1; node < node_count; ++node) {
    append_number(vocabulary.NodeParent(node));
    chunk += vocabulary.NodeIsLeaf(node) ? " 1" : " 0";
    const uint8_t* descriptor = vocabulary.NodeDescriptor(node);
    for (int b = 0; b < kFileDescriptorBytes; ++b) {
      chunk += ' ';
      append_number(static_cast<int>(descriptor[b]));
    }
    chunk += ' ';
    append_number(vocabulary.NodeWeight(node));
    chunk += '\n';
    if (chunk.size() >= kChunkBytes) {
      WriteAll(path, &file, chunk);
      chunk.clear();
    }
  }
  WriteAll(path, &file, chunk);
  CloseAfterWriting(path, &file);
}

void WriteBinaryVocabulary(const BowVocabulary& vocabulary, const std::string& path) {
  std::ofstream file = OpenForWriting(vocabulary, path);
  std::string chunk(kBinaryMagic, sizeof(kBinaryMagic));
  PutU32(kBinaryVersion, &chunk);
  PutU32(static_cast<uint32_t>(vocabulary.BranchingFactor()), &chunk);
  PutU32(static_cast<uint32_t>(vocabulary.Depth()), &chunk);
  PutU32(BowVocabulary::kL1Scoring, &chunk);
  PutU32(BowVocabulary::kTfIdfWeighting, &chunk);
  PutU64(vocabulary.NodeCount() - 1, &chunk);
  constexpr std::size_t kChunkBytes = 1 << 20;
  const int node_count = static_cast<int>(vocabulary.NodeCount());
  for (int node = 1; node < node_count; ++node) {
    PutU32(static_cast<uint32_t>(vocabulary.NodeParent(node)), &chunk);
    chunk.push_back(vocabulary.NodeIsLeaf(node) ? 1 : 0);
    chunk.append(reinterpret_cast<const char*>(vocabulary.NodeDescriptor(node)),
                 kFileDescriptorBytes);
    const double weight = vocabulary.NodeWeight(node);
    uint64_t weight_bits = 0;
    std::memcpy(&weight_bits, &weight, sizeof(weight));
    PutU64(weight_bits, &chunk);
    if (chunk.size() >= kChunkBytes) {
      WriteAll(path, &file, chunk);
      chunk.clear();
    }
  }
  WriteAll(path, &file, chunk);
  CloseAfterWriting(path, &file);
}

void WriteVocabulary(const BowVocabulary& vocabulary, const std::string& path,
                     VocabularyFormat format) {
  if (format == VocabularyFormat::kText) {
    WriteTextVocabulary(vocabulary, path);
  } else {
    WriteBinaryVocabulary(vocabulary, path);
  }
}

}  // namespace drvslam
