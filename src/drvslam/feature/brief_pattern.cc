#include "drvslam/feature/brief_pattern.h"

#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>

namespace drvslam {
namespace {

// SplitMix64: tiny, well mixed and fully specified, unlike std:: distributions whose output
// differs between standard libraries.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in (0, 1]: never 0, so log() below stays finite.
  double Uniform() {
    return (static_cast<double>(Next() >> 11) + 1.0) * (1.0 / 9007199254740992.0);
  }

 private:
  uint64_t state_;
};

// One offset drawn from N(0, sigma^2 I) (Box-Muller), rounded to a pixel and redrawn until it
// lies in the disc that stays inside the patch under any rotation.
struct Offset {
  int x, y;
};

Offset DrawOffset(SplitMix64& rng, double sigma) {
  constexpr int kR2 = kBriefPatchRadius * kBriefPatchRadius;
  constexpr double kTwoPi = 6.283185307179586;
  for (;;) {
    const double radius = sigma * std::sqrt(-2.0 * std::log(rng.Uniform()));
    const double phi = kTwoPi * rng.Uniform();
    const int x = static_cast<int>(std::lround(radius * std::cos(phi)));
    const int y = static_cast<int>(std::lround(radius * std::sin(phi)));
    if (x * x + y * y <= kR2) return {x, y};
  }
}

BriefPattern BuildPattern() {
  // BRIEF's best sampling geometry (isotropic Gaussian, sigma^2 = S^2 / 25 for patch size S).
  constexpr double kPatchSize = 2 * kBriefPatchRadius + 1;
  const double sigma = kPatchSize / 5.0;
  SplitMix64 rng(0x6472767331616dull);
  BriefPattern pattern{};
  std::set<std::tuple<int, int, int, int>> used;
  int n = 0;
  while (n < kBriefBits) {
    const Offset a = DrawOffset(rng, sigma);
    const Offset b = DrawOffset(rng, sigma);
    // A test against itself carries no information; a repeated (or swapped) pair only repeats
    // (or negates) another bit.
    if (a.x == b.x && a.y == b.y) continue;
    if (!used.insert({a.x, a.y, b.x, b.y}).second) continue;
    used.insert({b.x, b.y, a.x, a.y});
    pattern[n++] = {a.x, a.y, b.x, b.y};
  }
  return pattern;
}

}  // namespace

const BriefPattern& GetBriefPattern() {
  static const BriefPattern pattern = BuildPattern();
  return pattern;
}

}  // namespace drvslam
