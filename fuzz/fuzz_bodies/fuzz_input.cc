#include "fuzz_bodies/fuzz_input.h"

#include <algorithm>
#include <cstring>

namespace drvslam::fuzz {

std::uint8_t FuzzInput::Byte() { return offset_ < size_ ? data_[offset_++] : 0; }

std::uint32_t FuzzInput::U32() {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(Byte()) << (8 * i);
  return value;
}

double FuzzInput::Double() {
  std::uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(Byte()) << (8 * i);
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::string FuzzInput::ShortString(std::size_t max_length) {
  const std::size_t length = Byte() % (max_length + 1);
  const std::vector<std::uint8_t> bytes = Bytes(length);
  return std::string(bytes.begin(), bytes.end());
}

std::vector<std::uint8_t> FuzzInput::Bytes(std::size_t count) {
  const std::size_t taken = std::min(count, Remaining());
  std::vector<std::uint8_t> bytes(data_ + offset_, data_ + offset_ + taken);
  offset_ += taken;
  return bytes;
}

std::vector<std::uint8_t> FuzzInput::Rest() { return Bytes(Remaining()); }

std::vector<std::string> SplitInput(const std::uint8_t* data, std::size_t size,
                                    const std::string& separator, std::size_t parts) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> pieces;
  std::size_t start = 0;
  while (pieces.size() + 1 < parts) {
    const std::size_t at = text.find(separator, start);
    if (at == std::string::npos) break;
    pieces.push_back(text.substr(start, at - start));
    start = at + separator.size();
  }
  pieces.push_back(text.substr(start));
  return pieces;
}

}  // namespace drvslam::fuzz
