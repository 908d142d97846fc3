// ByteWriter and ByteReader: the little-endian binary encoding of map files, independent of the
// host's byte order. The reader checks every read against the bytes left, so a corrupt length
// or count becomes a drvslam::Error naming the file (never a read past the end or a huge
// allocation). Crc32 is the checksum map files end with (the zlib / PNG polynomial).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace drvslam {

class ByteWriter {
 public:
  void U8(uint8_t value) { buffer_.push_back(static_cast<char>(value)); }
  void U16(uint16_t value) { Unsigned(value, 2); }
  void U32(uint32_t value) { Unsigned(value, 4); }
  void U64(uint64_t value) { Unsigned(value, 8); }
  void I16(int16_t value) { Unsigned(static_cast<uint16_t>(value), 2); }
  void I32(int32_t value) { Unsigned(static_cast<uint32_t>(value), 4); }
  void I64(int64_t value) { Unsigned(static_cast<uint64_t>(value), 8); }
  void F32(float value);
  void F64(double value);
  void Bytes(const void* data, std::size_t size);
  // Length (u64) then the characters.
  void String(const std::string& text);

  std::size_t Size() const { return buffer_.size(); }
  const std::string& Buffer() const { return buffer_; }
  // Overwrites 8 bytes at `offset` (a length written before it was known).
  void PatchU64(std::size_t offset, uint64_t value);

 private:
  void Unsigned(uint64_t value, int bytes);

  std::string buffer_;
};

class ByteReader {
 public:
  // `context` starts every error message (e.g. "map.bin: section KFRM").
  ByteReader(const char* data, std::size_t size, std::string context);

  uint8_t U8();
  uint16_t U16() { return static_cast<uint16_t>(Unsigned(2)); }
  uint32_t U32() { return static_cast<uint32_t>(Unsigned(4)); }
  uint64_t U64() { return Unsigned(8); }
  int16_t I16() { return static_cast<int16_t>(Unsigned(2)); }
  int32_t I32() { return static_cast<int32_t>(Unsigned(4)); }
  int64_t I64() { return static_cast<int64_t>(Unsigned(8)); }
  float F32();
  double F64();
  void Bytes(void* out, std::size_t size);
  std::string String();
  void Skip(std::size_t size);
  // A count of elements that each take at least `min_element_bytes`: fails unless that many
  // could still follow.
  std::size_t Count(std::size_t min_element_bytes);

  std::size_t Remaining() const { return size_ - position_; }
  std::size_t Position() const { return position_; }
  const std::string& Context() const { return context_; }
  // Throws drvslam::Error: "<context>: corrupt map file: <what>".
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  uint64_t Unsigned(int bytes);
  void Need(std::size_t bytes) const;

  const char* data_;
  std::size_t size_;
  std::size_t position_ = 0;
  std::string context_;
};

// CRC-32 (polynomial 0xEDB88320, as zlib): Crc32(b, Crc32(a)) == Crc32(a + b).
uint32_t Crc32(const char* data, std::size_t size, uint32_t crc = 0);

// 64-bit FNV-1a, the hash of identities (settings, vocabulary): not cryptographic, only
// different for different content with overwhelming likelihood.
constexpr uint64_t kFnvOffsetBasis = 14695981039346656037ull;
uint64_t Fnv1a64(const void* data, std::size_t size, uint64_t hash = kFnvOffsetBasis);

}  // namespace drvslam
