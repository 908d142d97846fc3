// Counter-based random numbers for per-pixel effects (sensor noise, dropped depth): a value
// depends only on its key (seed, frame, pixel, channel), never on the order pixels are visited,
// so an image comes out the same on any number of threads. Integer arithmetic only, so it also
// comes out the same on every platform.
#pragma once

#include <cstdint>

namespace drvslam::synth {

// The splitmix64 finalizer: a bijective mix whose output bits all depend on every input bit.
inline uint64_t MixBits(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Combines key parts into one well-mixed value; distinct keys give independent-looking values.
inline uint64_t HashKey(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0) {
  return MixBits(MixBits(MixBits(MixBits(a) ^ b) ^ c) ^ d);
}

// Uniform in [0, 1) from the top 24 bits.
inline float HashUniform(uint64_t h) { return static_cast<float>(h >> 40) * (1.0f / 16777216.0f); }

// Approximately standard normal: the Irwin-Hall sum of four 16-bit uniforms, rescaled to unit
// variance. Its tails stop at +-3.46 sigma, which suits sensor noise (no wild outliers).
inline float HashGaussian(uint64_t h) {
  const float sum = static_cast<float>(h & 0xFFFF) + static_cast<float>((h >> 16) & 0xFFFF) +
                    static_cast<float>((h >> 32) & 0xFFFF) + static_cast<float>(h >> 48);
  constexpr float kMean = 2.0f * 65535.0f;
  constexpr float kScale = 1.7320508f / 65535.0f;  // sqrt(12 / 4) per unit range
  return (sum - kMean) * kScale;
}

}  // namespace drvslam::synth
