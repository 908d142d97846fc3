#include "drvslam/mapfile/byte_codec.h"

#include <array>
#include <cstring>
#include <utility>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

std::array<uint32_t, 256> MakeCrcTable() {
  std::array<uint32_t, 256> table{};
  for (uint32_t n = 0; n < 256; ++n) {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

}  // namespace

void ByteWriter::Unsigned(uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) buffer_.push_back(static_cast<char>((value >> (8 * i)) & 0xffu));
}

void ByteWriter::F32(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  U32(bits);
}

void ByteWriter::F64(double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  U64(bits);
}

void ByteWriter::Bytes(const void* data, std::size_t size) {
  buffer_.append(static_cast<const char*>(data), size);
}

void ByteWriter::String(const std::string& text) {
  U64(text.size());
  buffer_.append(text);
}

void ByteWriter::PatchU64(std::size_t offset, uint64_t value) {
  for (int i = 0; i < 8; ++i) {
    buffer_[offset + i] = static_cast<char>((value >> (8 * i)) & 0xffu);
  }
}

ByteReader::ByteReader(const char* data, std::size_t size, std::string context)
    : data_(data), size_(size), context_(std::move(context)) {}

void ByteReader::Fail(const std::string& what) const {
  throw Error(context_ + ": corrupt map file: " + what);
}

void ByteReader::Need(std::size_t bytes) const {
  if (bytes > Remaining()) {
    Fail("needs " + std::to_string(bytes) + " more bytes at offset " + std::to_string(position_) +
         ", " + std::to_string(Remaining()) + " left");
  }
}

uint64_t ByteReader::Unsigned(int bytes) {
  Need(static_cast<std::size_t>(bytes));
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    value |= static_cast<uint64_t>(static_cast<unsigned char>(data_[position_ + i])) << (8 * i);
  }
  position_ += static_cast<std::size_t>(bytes);
  return value;
}

uint8_t ByteReader::U8() { return static_cast<uint8_t>(Unsigned(1)); }

float ByteReader::F32() {
  const uint32_t bits = U32();
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

double ByteReader::F64() {
  const uint64_t bits = U64();
  double value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

void ByteReader::Bytes(void* out, std::size_t size) {
  Need(size);
  std::memcpy(out, data_ + position_, size);
  position_ += size;
}

void ByteReader::Skip(std::size_t size) {
  Need(size);
  position_ += size;
}

std::string ByteReader::String() {
  const std::size_t size = Count(1);
  std::string text(data_ + position_, size);
  position_ += size;
  return text;
}

std::size_t ByteReader::Count(std::size_t min_element_bytes) {
  const uint64_t count = U64();
  const uint64_t per = min_element_bytes == 0 ? 1 : min_element_bytes;
  if (count > Remaining() / per) {
    Fail("a count of " + std::to_string(count) + " at offset " + std::to_string(position_ - 8) +
         " does not fit the " + std::to_string(Remaining()) + " bytes left");
  }
  return static_cast<std::size_t>(count);
}

uint32_t Crc32(const char* data, std::size_t size, uint32_t crc) {
  static const std::array<uint32_t, 256> kTable = MakeCrcTable();
  uint32_t c = crc ^ 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) {
    c = kTable[(c ^ static_cast<unsigned char>(data[i])) & 0xffu] ^ (c >> 8);
  }
  return c ^ 0xFFFFFFFFu;
}

uint64_t Fnv1a64(const void* data, std::size_t size, uint64_t hash) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace drvslam
