// FuzzInput: fuzz bytes read front to back as the fields of a structured input (numbers,
// short strings, the rest as a blob). Reading past the end gives zeros and empty strings, so
// every byte string is some input and libFuzzer's mutations change one field at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace drvslam::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t Byte();
  std::uint32_t U32();
  double Double();
  // A string of up to `max_length` bytes: one length byte (modulo max_length + 1), then the
  // bytes.
  std::string ShortString(std::size_t max_length);
  // Up to `count` bytes, fewer when the input ends.
  std::vector<std::uint8_t> Bytes(std::size_t count);
  // Everything not read yet.
  std::vector<std::uint8_t> Rest();
  std::size_t Remaining() const { return size_ - offset_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

// The input split into at most `parts` pieces at each occurrence of `separator` (the last piece
// keeps any further separators). Lets one input hold several files.
std::vector<std::string> SplitInput(const std::uint8_t* data, std::size_t size,
                                    const std::string& separator, std::size_t parts);

}  // namespace drvslam::fuzz
