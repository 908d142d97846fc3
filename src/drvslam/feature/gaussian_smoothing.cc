#include "drvslam/feature/gaussian_smoothing.h"

#include <array>
#include <cmath>

#include "drvslam/core/error.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace drvslam {
namespace {

constexpr int kTaps = 7;
constexpr int kHalf = kTaps / 2;

// The kernel in Q16 fixed point (sum exactly 65536). Both passes multiply 16-bit values by it
// and keep the high 16 bits of each product: the vertical pass weighs pixels scaled by 256, so
// its sums are Q8 grey levels (at most 65280: they fit 16 bits unsigned), and the horizontal
// pass weighs those sums the same way. Truncation costs under 7/256 of a grey level per pass.
using Kernel = std::array<uint16_t, kTaps>;

const Kernel& GetKernel() {
  static const Kernel kernel = [] {
    constexpr double kSigma = 2.0;
    std::array<double, kTaps> g{};
    double sum = 0.0;
    for (int k = 0; k < kTaps; ++k) {
      g[k] = std::exp(-(k - kHalf) * (k - kHalf) / (2.0 * kSigma * kSigma));
      sum += g[k];
    }
    Kernel q{};
    int total = 0;
    for (int k = 0; k < kTaps; ++k) {
      q[k] = static_cast<uint16_t>(std::lround(g[k] / sum * 65536.0));
      total += q[k];
    }
    q[kHalf] = static_cast<uint16_t>(q[kHalf] + 65536 - total);  // the rounding residue
    return q;
  }();
  return kernel;
}

// BORDER_REFLECT_101 index for any n >= 1.
int Reflect101(int i, int n) {
  if (n == 1) return 0;
  while (i < 0 || i >= n) i = i < 0 ? -i : 2 * n - 2 - i;
  return i;
}

// Vertical pass of one output row into buf[kHalf .. kHalf + cols).
void VerticalPass(const uint8_t* const* rows, int cols, const Kernel& k, uint16_t* buf) {
  int x = 0;
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  for (; x + 16 <= cols; x += 16) {
    __m128i lo = zero;
    __m128i hi = zero;
    for (int t = 0; t < kTaps; ++t) {
      const __m128i w = _mm_set1_epi16(static_cast<int16_t>(k[t]));
      const __m128i p = _mm_loadu_si128(reinterpret_cast<const __m128i*>(rows[t] + x));
      // Interleaving zero below each byte gives the byte * 256.
      lo = _mm_add_epi16(lo, _mm_mulhi_epu16(_mm_unpacklo_epi8(zero, p), w));
      hi = _mm_add_epi16(hi, _mm_mulhi_epu16(_mm_unpackhi_epi8(zero, p), w));
    }
    _mm_storeu_si128(reinterpret_cast<__m128i*>(buf + kHalf + x), lo);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(buf + kHalf + x + 8), hi);
  }
#endif
  for (; x < cols; ++x) {
    uint32_t sum = 0;
    for (int t = 0; t < kTaps; ++t) sum += (static_cast<uint32_t>(rows[t][x]) * 256 * k[t]) >> 16;
    buf[kHalf + x] = static_cast<uint16_t>(sum);
  }
}

// Horizontal pass over buf (already padded by kHalf reflected entries on each side).
void HorizontalPass(const uint16_t* buf, int cols, const Kernel& k, uint8_t* out) {
  int x = 0;
#if defined(__SSE2__)
  const __m128i round = _mm_set1_epi16(128);
  for (; x + 8 <= cols; x += 8) {
    __m128i sum = _mm_setzero_si128();
    for (int t = 0; t < kTaps; ++t) {
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(buf + x + t));
      sum = _mm_add_epi16(sum, _mm_mulhi_epu16(v, _mm_set1_epi16(static_cast<int16_t>(k[t]))));
    }
    const __m128i pixels = _mm_srli_epi16(_mm_add_epi16(sum, round), 8);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + x), _mm_packus_epi16(pixels, pixels));
  }
#endif
  for (; x < cols; ++x) {
    uint32_t sum = 0;
    for (int t = 0; t < kTaps; ++t) sum += (static_cast<uint32_t>(buf[x + t]) * k[t]) >> 16;
    out[x] = static_cast<uint8_t>((sum + 128) >> 8);
  }
}

}  // namespace

void SmoothGaussian7(const cv::Mat& src, cv::Mat* dst, std::vector<uint16_t>* row_buffer) {
  if (src.type() != CV_8UC1 || dst == nullptr || (src.data != nullptr && src.data == dst->data)) {
    throw Error("SmoothGaussian7: needs a CV_8UC1 source and a separate destination");
  }
  const Kernel& k = GetKernel();
  const int rows = src.rows;
  const int cols = src.cols;
  dst->create(src.size(), CV_8UC1);
  row_buffer->resize(static_cast<size_t>(cols) + 2 * kHalf);
  uint16_t* buf = row_buffer->data();
  const uint8_t* taps[kTaps];
  for (int y = 0; y < rows; ++y) {
    for (int t = 0; t < kTaps; ++t) taps[t] = src.ptr<uint8_t>(Reflect101(y + t - kHalf, rows));
    VerticalPass(taps, cols, k, buf);
    for (int i = 1; i <= kHalf; ++i) {
      buf[kHalf - i] = buf[kHalf + Reflect101(-i, cols)];
      buf[kHalf + cols - 1 + i] = buf[kHalf + Reflect101(cols - 1 + i, cols)];
    }
    HorizontalPass(buf, cols, k, dst->ptr<uint8_t>(y));
  }
}

}  // namespace drvslam
