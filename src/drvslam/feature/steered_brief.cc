#include "drvslam/feature/steered_brief.h"

#include <array>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "drvslam/feature/brief_pattern.h"

namespace drvslam {
namespace {

constexpr float kDegPerRad = 57.29577951308232f;
constexpr int kR = kBriefPatchRadius;

// Half-width of the disc row at each |v|: the largest u with u^2 + v^2 <= r^2. Integer-exact, so
// the disc is symmetric under 90-degree rotations and orientations rotate with the image.
std::array<int, kR + 1> DiscHalfWidths() {
  std::array<int, kR + 1> half{};
  for (int v = 0; v <= kR; ++v) {
    int u = 0;
    while ((u + 1) * (u + 1) + v * v <= kR * kR) ++u;
    half[v] = u;
  }
  return half;
}

const std::array<int, kR + 1>& HalfWidths() {
  static const std::array<int, kR + 1> half = DiscHalfWidths();
  return half;
}

// The pattern as float coordinate arrays (first points, then second points), the layout the
// vectorized rotation below reads.
struct PatternCoordinates {
  alignas(16) float x[2 * kBriefBits];
  alignas(16) float y[2 * kBriefBits];
};

const PatternCoordinates& Coordinates() {
  static const PatternCoordinates coords = [] {
    PatternCoordinates c;
    const BriefPattern& pattern = GetBriefPattern();
    for (int i = 0; i < kBriefBits; ++i) {
      c.x[i] = static_cast<float>(pattern[i].x1);
      c.y[i] = static_cast<float>(pattern[i].y1);
      c.x[kBriefBits + i] = static_cast<float>(pattern[i].x2);
      c.y[kBriefBits + i] = static_cast<float>(pattern[i].y2);
    }
    return c;
  }();
  return coords;
}

// Pixel offsets (dy * step + dx) of all 512 samples rotated by (c, s), each coordinate rounded
// to nearest (ties to even, as cvRound does), first points in [0, 256), second in [256, 512).
void RotatedOffsets(float c, float s, int step, int* offsets) {
  const PatternCoordinates& p = Coordinates();
#if defined(__SSE2__)
  const __m128 vc = _mm_set1_ps(c);
  const __m128 vs = _mm_set1_ps(s);
  const __m128 vstep = _mm_set1_ps(static_cast<float>(step));
  for (int i = 0; i < 2 * kBriefBits; i += 4) {
    const __m128 x = _mm_load_ps(p.x + i);
    const __m128 y = _mm_load_ps(p.y + i);
    const __m128i rx = _mm_cvtps_epi32(_mm_sub_ps(_mm_mul_ps(x, vc), _mm_mul_ps(y, vs)));
    const __m128i ry = _mm_cvtps_epi32(_mm_add_ps(_mm_mul_ps(x, vs), _mm_mul_ps(y, vc)));
    // dy * step + dx in float is exact: |value| < 2^24 for any image a level can hold.
    const __m128 offset = _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(ry), vstep), _mm_cvtepi32_ps(rx));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(offsets + i), _mm_cvtps_epi32(offset));
  }
#else
  for (int i = 0; i < 2 * kBriefBits; ++i) {
    offsets[i] = cvRound(p.x[i] * s + p.y[i] * c) * step + cvRound(p.x[i] * c - p.y[i] * s);
  }
#endif
}

}  // namespace

float IntensityCentroidAngle(const cv::Mat& image, int x, int y) {
  const std::array<int, kR + 1>& half = HalfWidths();
  const uint8_t* center = image.ptr<uint8_t>(y) + x;
  const ptrdiff_t step = static_cast<ptrdiff_t>(image.step1());
  int m10 = 0;
  int m01 = 0;
#if defined(__SSE2__)
  // 32 pixels per row, u = -15 .. 16, starting at u = -15; the bytes outside the disc row are
  // masked to zero (u = 16 always is). Reading u = 16 stays inside the level because corners
  // keep kR + 1 pixels from its edges.
  struct RowMasks {
    alignas(16) uint8_t bytes[kR + 1][32];
  };
  static const RowMasks masks = [] {
    RowMasks m{};
    for (int v = 0; v <= kR; ++v) {
      for (int i = 0; i < 32; ++i) m.bytes[v][i] = std::abs(i - kR) <= HalfWidths()[v] ? 0xFF : 0;
    }
    return m;
  }();
  const __m128i zero = _mm_setzero_si128();
  const __m128i u0 = _mm_setr_epi16(-15, -14, -13, -12, -11, -10, -9, -8);
  const __m128i u1 = _mm_setr_epi16(-7, -6, -5, -4, -3, -2, -1, 0);
  const __m128i u2 = _mm_setr_epi16(1, 2, 3, 4, 5, 6, 7, 8);
  const __m128i u3 = _mm_setr_epi16(9, 10, 11, 12, 13, 14, 15, 16);
  __m128i acc10 = zero;
  __m128i acc01 = zero;
  for (int v = 0; v <= kR; ++v) {
    const __m128i mask_lo = _mm_load_si128(reinterpret_cast<const __m128i*>(masks.bytes[v]));
    const __m128i mask_hi = _mm_load_si128(reinterpret_cast<const __m128i*>(masks.bytes[v] + 16));
    const uint8_t* below = center + v * step - kR;
    const uint8_t* above = center - v * step - kR;
    const __m128i b_lo =
        _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(below)), mask_lo);
    const __m128i b_hi =
        _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(below + 16)), mask_hi);
    // Row 0 counts once: its "above" is a zero row.
    const __m128i a_lo =
        v == 0 ? zero
               : _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(above)), mask_lo);
    const __m128i a_hi =
        v == 0
            ? zero
            : _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(above + 16)), mask_hi);
    const __m128i b0 = _mm_unpacklo_epi8(b_lo, zero), b1 = _mm_unpackhi_epi8(b_lo, zero);
    const __m128i b2 = _mm_unpacklo_epi8(b_hi, zero), b3 = _mm_unpackhi_epi8(b_hi, zero);
    const __m128i a0 = _mm_unpacklo_epi8(a_lo, zero), a1 = _mm_unpackhi_epi8(a_lo, zero);
    const __m128i a2 = _mm_unpacklo_epi8(a_hi, zero), a3 = _mm_unpackhi_epi8(a_hi, zero);
    // x-moment: u * (below + above); y-moment: v * (below - above).
    acc10 = _mm_add_epi32(acc10, _mm_madd_epi16(_mm_add_epi16(a0, b0), u0));
    acc10 = _mm_add_epi32(acc10, _mm_madd_epi16(_mm_add_epi16(a1, b1), u1));
    acc10 = _mm_add_epi32(acc10, _mm_madd_epi16(_mm_add_epi16(a2, b2), u2));
    acc10 = _mm_add_epi32(acc10, _mm_madd_epi16(_mm_add_epi16(a3, b3), u3));
    const __m128i diff = _mm_add_epi16(_mm_add_epi16(_mm_sub_epi16(b0, a0), _mm_sub_epi16(b1, a1)),
                                       _mm_add_epi16(_mm_sub_epi16(b2, a2), _mm_sub_epi16(b3, a3)));
    acc01 = _mm_add_epi32(acc01, _mm_madd_epi16(diff, _mm_set1_epi16(static_cast<int16_t>(v))));
  }
  alignas(16) int lanes10[4];
  alignas(16) int lanes01[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(lanes10), acc10);
  _mm_store_si128(reinterpret_cast<__m128i*>(lanes01), acc01);
  m10 = lanes10[0] + lanes10[1] + lanes10[2] + lanes10[3];
  m01 = lanes01[0] + lanes01[1] + lanes01[2] + lanes01[3];
#else
  for (int u = -kR; u <= kR; ++u) m10 += u * center[u];
  // Rows +v and -v together: their x-moments add, their y-moments subtract.
  for (int v = 1; v <= kR; ++v) {
    const uint8_t* below = center + v * step;
    const uint8_t* above = center - v * step;
    const int d = half[v];
    int row_diff = 0;
    for (int u = -d; u <= d; ++u) {
      m10 += u * (above[u] + below[u]);
      row_diff += below[u] - above[u];
    }
    m01 += v * row_diff;
  }
#endif
  (void)half;
  if (m10 == 0 && m01 == 0) return 0.0f;
  float angle = std::atan2(static_cast<float>(m01), static_cast<float>(m10)) * kDegPerRad;
  if (angle < 0.0f) angle += 360.0f;
  if (angle >= 360.0f) angle = 0.0f;  // -tiny + 360 rounds up to 360
  return angle;
}

void ComputeSteeredBrief(const cv::Mat& smoothed, int x, int y, float angle_deg, uint8_t* out) {
  const float radians = angle_deg / kDegPerRad;
  const uint8_t* center = smoothed.ptr<uint8_t>(y) + x;
  alignas(16) int offsets[2 * kBriefBits];
  RotatedOffsets(std::cos(radians), std::sin(radians), static_cast<int>(smoothed.step1()), offsets);
  const int* first = offsets;
  const int* second = offsets + kBriefBits;
  for (int byte = 0; byte < kBriefBits / 8; ++byte) {
    int value = 0;
    for (int bit = 0; bit < 8; ++bit) {
      const int i = 8 * byte + bit;
      value |= (center[first[i]] < center[second[i]]) << bit;
    }
    out[byte] = static_cast<uint8_t>(value);
  }
}

}  // namespace drvslam
