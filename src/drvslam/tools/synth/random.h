// Random: the generator's source of scene randomness (textures, layout details, actor
// behaviour), std::mt19937 seeded from --seed. The distributions are written here rather than
// taken from <random>, whose distributions differ between standard libraries, so a seed builds
// the same scene with any compiler.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "drvslam/tools/synth/hash_noise.h"

namespace drvslam::synth {

// Named sub-streams: each part of the scene draws from its own stream, so adding actors never
// changes the room's textures or the camera path (a dynamic scenario and its static counterpart
// then share everything but the movers).
enum class RandomStream : uint64_t {
  kTextures = 1,
  kLayout = 2,
  kCameraPath = 3,
  kActors = 4,
  kSensor = 5,
  kActorTextures = 6,
  kCartTextures = 7,
};

// A 32-bit seed for one sub-stream (and optional index within it) of the user's seed.
inline uint32_t SubSeed(uint64_t seed, RandomStream stream, uint64_t index = 0) {
  return static_cast<uint32_t>(HashKey(seed, static_cast<uint64_t>(stream), index) >> 32);
}

class Random {
 public:
  explicit Random(uint32_t seed) : engine_(seed) {}

  uint32_t Bits() { return static_cast<uint32_t>(engine_()); }
  // 64 bits from two draws, the first in the high half. Drawn in two statements: the operands of
  // one expression (a() << 32 | a()) are evaluated in an order the compiler chooses.
  uint64_t Bits64() {
    const uint64_t high = Bits();
    const uint64_t low = Bits();
    return (high << 32) | low;
  }
  // Uniform in [0, 1) with 53 random bits.
  double Uniform() {
    const uint64_t high = Bits() >> 5;
    const uint64_t low = Bits() >> 6;
    return static_cast<double>((high << 26) | low) * (1.0 / 9007199254740992.0);
  }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [lo, hi] (inclusive); lo when hi < lo.
  int UniformInt(int lo, int hi) {
    if (hi <= lo) return lo;
    const uint64_t span = static_cast<uint64_t>(hi - lo) + 1;
    return lo +
           static_cast<int>(static_cast<uint64_t>(Uniform() * static_cast<double>(span)) % span);
  }
  bool Chance(double probability) { return Uniform() < probability; }
  // Log-uniform in [lo, hi], both positive: as many small sizes per octave as large ones.
  double LogUniform(double lo, double hi) { return lo * std::exp(Uniform() * std::log(hi / lo)); }
  // Standard normal (Box-Muller).
  double Normal() {
    const double u1 = 1.0 - Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  template <typename T>
  const T& Pick(const std::vector<T>& items) {
    return items[static_cast<std::size_t>(UniformInt(0, static_cast<int>(items.size()) - 1))];
  }

 private:
  std::mt19937 engine_;
};

}  // namespace drvslam::synth
