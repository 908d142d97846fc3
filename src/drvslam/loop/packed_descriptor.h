// A 256-bit ORB descriptor held as four 64-bit words, the layout the vocabulary tree and its
// trainer compare and vote on. Bytes map to words with memcpy, so PackDescriptor and
// UnpackDescriptor are exact inverses and Hamming distances equal DescriptorDistance's.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

namespace drvslam {

using PackedDescriptor = std::array<uint64_t, 4>;

inline PackedDescriptor PackDescriptor(const uint8_t* bytes) {
  PackedDescriptor packed;
  std::memcpy(packed.data(), bytes, sizeof(packed));
  return packed;
}

inline void UnpackDescriptor(const PackedDescriptor& packed, uint8_t* bytes) {
  std::memcpy(bytes, packed.data(), sizeof(packed));
}

// Bit count without relying on a popcnt instruction the build may not target.
inline int PopCount64(uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

inline int HammingDistance(const PackedDescriptor& a, const PackedDescriptor& b) {
  return PopCount64(a[0] ^ b[0]) + PopCount64(a[1] ^ b[1]) + PopCount64(a[2] ^ b[2]) +
         PopCount64(a[3] ^ b[3]);
}

}  // namespace drvslam
