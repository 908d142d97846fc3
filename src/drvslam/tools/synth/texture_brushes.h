// The brushes texture_painter.cc paints its styles with: the request's texel scale, random
// colours, value-noise octaves, grain, shapes, glyphs, photo crops, printed pages and pasting.
// Kept apart from the styles so that each file has one job; only texture_painter.cc includes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/tools/synth/hash_noise.h"
#include "drvslam/tools/synth/photo_library.h"
#include "drvslam/tools/synth/random.h"
#include "drvslam/tools/synth/texture_painter.h"

namespace drvslam::synth::painting {

// One octave of value noise: random values on a grid of `cell`-texel squares, interpolated
// bicubically. `colour` draws each channel independently, otherwise all three move together.
struct Octave {
  double cell_m;
  double amplitude;
  bool colour;
};

struct TextureBrushes {
  TextureBrushes(const TextureRequest& request, const PhotoLibrary& photos)
      : request(request),
        photos(photos),
        rng(request.seed),
        size(request.PixelSize()),
        density(static_cast<double>(size.width) / std::max(request.width_m, 1e-6)),
        area_m2(request.width_m * request.height_m) {}

  const TextureRequest& request;
  const PhotoLibrary& photos;
  Random rng;
  cv::Size size;
  double density;  // texels per metre after the max_side cap
  double area_m2;

  double Px(double metres) const { return metres * density; }

  cv::Scalar RandomColour(double min_value = 0.08, double max_value = 1.0,
                          double min_saturation = 0.15) {
    const double hue = rng.Uniform(0.0, 6.0);
    const double saturation = rng.Uniform(min_saturation, 1.0);
    const double value = rng.Uniform(min_value, max_value);
    const double chroma = value * saturation;
    const double x = chroma * (1.0 - std::fabs(std::fmod(hue, 2.0) - 1.0));
    double r = 0, g = 0, b = 0;
    switch (static_cast<int>(hue)) {
      case 0:
        r = chroma, g = x;
        break;
      case 1:
        r = x, g = chroma;
        break;
      case 2:
        g = chroma, b = x;
        break;
      case 3:
        g = x, b = chroma;
        break;
      case 4:
        r = x, b = chroma;
        break;
      default:
        r = chroma, b = x;
        break;
    }
    const double m = value - chroma;
    return cv::Scalar(255.0 * (b + m), 255.0 * (g + m), 255.0 * (r + m));
  }

  static double Luma(const cv::Scalar& c) { return 0.114 * c[0] + 0.587 * c[1] + 0.299 * c[2]; }

  // A colour whose brightness differs clearly from `base`, so shapes stand out as corners.
  cv::Scalar Contrasting(const cv::Scalar& base) {
    const bool darker = Luma(base) > 128.0;
    for (int attempt = 0; attempt < 8; ++attempt) {
      const cv::Scalar c = darker ? RandomColour(0.0, 0.45) : RandomColour(0.6, 1.0);
      if (std::fabs(Luma(c) - Luma(base)) > 70.0) return c;
    }
    return darker ? cv::Scalar(20, 20, 20) : cv::Scalar(235, 235, 235);
  }

  // One octave, upsampled to the texture size: CV_32FC3 for colour octaves, else CV_32FC1.
  cv::Mat OctaveImage(const Octave& octave) {
    const double cell = std::max(1.0, Px(octave.cell_m));
    const int grid_w = static_cast<int>(std::ceil(size.width / cell)) + 2;
    const int grid_h = static_cast<int>(std::ceil(size.height / cell)) + 2;
    cv::Mat grid(grid_h, grid_w, octave.colour ? CV_32FC3 : CV_32FC1);
    // OpenCV's generator (a fixed multiply-with-carry) seeded from ours fills large grids fast
    // and just as reproducibly.
    cv::RNG fill_rng(rng.Bits64());
    fill_rng.fill(grid, cv::RNG::UNIFORM, -octave.amplitude, octave.amplitude);
    if (cell <= 1.0) return grid(cv::Rect(0, 0, size.width, size.height));
    cv::Mat up;
    cv::resize(grid, up, cv::Size(static_cast<int>(grid_w * cell), static_cast<int>(grid_h * cell)),
               0, 0, cv::INTER_CUBIC);
    return up(cv::Rect(0, 0, size.width, size.height));
  }

  // `base` plus the octaves, converted to 8 bits. Luminance octaves are summed in one channel
  // and spread to the three at the end, which halves the work.
  cv::Mat NoiseImage(const cv::Scalar& base, const std::vector<Octave>& octaves) {
    cv::Mat colour(size, CV_32FC3, base);
    cv::Mat luminance(size, CV_32FC1, cv::Scalar(0.0));
    for (const Octave& octave : octaves) {
      if (octave.colour) {
        colour += OctaveImage(octave);
      } else {
        luminance += OctaveImage(octave);
      }
    }
    cv::Mat spread;
    cv::cvtColor(luminance, spread, cv::COLOR_GRAY2BGR);
    colour += spread;
    cv::Mat image;
    colour.convertTo(image, CV_8UC3);
    return image;
  }

  // Texel-scale luminance grain over the finished image, so that no area is perfectly flat.
  void AddGrain(cv::Mat* image, double amplitude) {
    const uint64_t key = rng.Bits64();
    const float scale = static_cast<float>(2.0 * amplitude);
    for (int y = 0; y < image->rows; ++y) {
      uint8_t* row = image->ptr<uint8_t>(y);
      for (int x = 0; x < image->cols; ++x) {
        const uint64_t h = MixBits(key ^ (static_cast<uint64_t>(y) * image->cols + x));
        // Rounded via a positive shift: truncation then equals floor.
        const int offset = static_cast<int>((HashUniform(h) - 0.5f) * scale + 256.5f) - 256;
        for (int c = 0; c < 3; ++c) {
          row[3 * x + c] = static_cast<uint8_t>(std::clamp(row[3 * x + c] + offset, 0, 255));
        }
      }
    }
  }

  cv::Point Fixed(double x, double y) const {
    // Drawing coordinates with 3 fractional bits keep anti-aliased edges at sub-texel positions.
    return cv::Point(static_cast<int>(std::lround(x * 8.0)),
                     static_cast<int>(std::lround(y * 8.0)));
  }

  void DrawShape(cv::Mat* image, double size_px, const cv::Scalar& colour) {
    constexpr int kShift = 3;
    // Anti-aliasing matters for small fills, whose edges are a large share of their area; big
    // fills without it cost several times less. Outlines and strokes are always smoothed.
    const int line_type = size_px > 32.0 ? cv::LINE_8 : cv::LINE_AA;
    const double cx = rng.Uniform(-0.2 * size_px, image->cols + 0.2 * size_px);
    const double cy = rng.Uniform(-0.2 * size_px, image->rows + 0.2 * size_px);
    const double r = 0.5 * size_px;
    const int thickness = std::max(1, static_cast<int>(std::lround(rng.Uniform(0.06, 0.2) * r)));
    switch (rng.UniformInt(0, 6)) {
      case 0:
        cv::circle(*image, Fixed(cx, cy), static_cast<int>(r * 8.0), colour, cv::FILLED, line_type,
                   kShift);
        break;
      case 1:
        cv::ellipse(
            *image, Fixed(cx, cy),
            cv::Size(static_cast<int>(r * 8.0), static_cast<int>(r * rng.Uniform(0.25, 0.9) * 8.0)),
            rng.Uniform(0.0, 180.0), 0.0, 360.0, colour, cv::FILLED, line_type, kShift);
        break;
      case 2:
      case 3: {
        // A convex polygon (3 to 6 corners) or a rotated rectangle.
        const int corners = rng.UniformInt(3, 6);
        const double start = rng.Uniform(0.0, 6.283185307179586);
        std::vector<cv::Point> points;
        for (int k = 0; k < corners; ++k) {
          const double angle = start + 6.283185307179586 * (k + rng.Uniform(-0.25, 0.25)) / corners;
          const double radius = r * rng.Uniform(0.7, 1.0);
          points.push_back(Fixed(cx + radius * std::cos(angle), cy + radius * std::sin(angle)));
        }
        cv::fillPoly(*image, std::vector<std::vector<cv::Point>>{points}, colour, line_type,
                     kShift);
        break;
      }
      case 4: {
        // A stroke: a short random walk, like a pen line.
        std::vector<cv::Point> points;
        double x = cx, y = cy;
        double heading = rng.Uniform(0.0, 6.283185307179586);
        const int segments = rng.UniformInt(2, 7);
        points.push_back(Fixed(x, y));
        for (int k = 0; k < segments; ++k) {
          heading += rng.Uniform(-1.3, 1.3);
          const double step = r * rng.Uniform(0.3, 0.9);
          x += step * std::cos(heading);
          y += step * std::sin(heading);
          points.push_back(Fixed(x, y));
        }
        cv::polylines(*image, points, false, colour, thickness, cv::LINE_AA, kShift);
        break;
      }
      case 5:
        cv::circle(*image, Fixed(cx, cy), static_cast<int>(r * 8.0), colour, thickness, cv::LINE_AA,
                   kShift);
        break;
      default: {
        const cv::RotatedRect box(cv::Point2f(static_cast<float>(cx), static_cast<float>(cy)),
                                  cv::Size2f(static_cast<float>(2.0 * r),
                                             static_cast<float>(2.0 * r * rng.Uniform(0.3, 1.0))),
                                  static_cast<float>(rng.Uniform(0.0, 180.0)));
        cv::Point2f corners[4];
        box.points(corners);
        std::vector<cv::Point> points;
        for (const cv::Point2f& p : corners) points.push_back(Fixed(p.x, p.y));
        cv::polylines(*image, points, true, colour, thickness, cv::LINE_AA, kShift);
        break;
      }
    }
  }

  void DrawGlyphs(cv::Mat* image, double height_px, const cv::Scalar& colour, int length) {
    static const char kAlphabet[] = "ABCDEFGHJKLMNPQRSTUVWXYZabdefghkmnpqrstuvwxyz0123456789#&%@?";
    static const int kFonts[] = {cv::FONT_HERSHEY_SIMPLEX,        cv::FONT_HERSHEY_DUPLEX,
                                 cv::FONT_HERSHEY_COMPLEX,        cv::FONT_HERSHEY_TRIPLEX,
                                 cv::FONT_HERSHEY_SCRIPT_SIMPLEX, cv::FONT_HERSHEY_PLAIN};
    std::string text;
    for (int k = 0; k < length; ++k) {
      text += kAlphabet[rng.UniformInt(0, static_cast<int>(sizeof(kAlphabet)) - 2)];
    }
    const int font = kFonts[rng.UniformInt(0, 5)];
    const double scale = std::max(0.15, height_px / 22.0);
    const int thickness = std::max(1, static_cast<int>(std::lround(scale * rng.Uniform(1.0, 2.5))));
    const cv::Point origin(static_cast<int>(rng.Uniform(-height_px, image->cols)),
                           static_cast<int>(rng.Uniform(0.0, image->rows + height_px)));
    cv::putText(*image, text, origin, font, scale, colour, thickness, cv::LINE_AA);
  }

  // Shapes with log-uniform sizes between min_m and max_m, drawn largest first so that small
  // ones stay visible on top.
  void DrawShapes(cv::Mat* image, int count, double min_m, double max_m,
                  const std::vector<cv::Scalar>& palette = {}) {
    std::vector<double> sizes(static_cast<std::size_t>(std::max(count, 0)));
    for (double& s : sizes) s = Px(rng.LogUniform(min_m, max_m));
    std::sort(sizes.begin(), sizes.end(), std::greater<double>());
    for (const double s : sizes) {
      const cv::Scalar colour = palette.empty() ? RandomColour() : rng.Pick(palette);
      DrawShape(image, std::max(s, 1.5), colour);
    }
  }

  void DrawGlyphRuns(cv::Mat* image, int count, double min_m, double max_m,
                     const std::vector<cv::Scalar>& palette = {}) {
    for (int k = 0; k < count; ++k) {
      const cv::Scalar colour = palette.empty() ? RandomColour() : rng.Pick(palette);
      DrawGlyphs(image, Px(rng.LogUniform(min_m, max_m)), colour, rng.UniformInt(1, 7));
    }
  }

  int PerArea(double per_m2) const { return static_cast<int>(std::lround(per_m2 * area_m2)); }

  // A crop of a random photograph, at about one photo pixel per texel, turned, mirrored and
  // colour-cast at random so that two crops of one photo still differ.
  cv::Mat PhotoPatch(int width, int height) {
    const cv::Mat& photo = photos.Photo(rng.UniformInt(0, photos.Size() - 1));
    const int quarter_turns = rng.UniformInt(0, 3);
    const bool mirror = rng.Chance(0.5);
    const double texels_per_pixel = rng.Uniform(0.7, 1.4);
    int crop_w = static_cast<int>((quarter_turns % 2 ? height : width) / texels_per_pixel);
    int crop_h = static_cast<int>((quarter_turns % 2 ? width : height) / texels_per_pixel);
    const double fit =
        std::min(1.0, std::min(static_cast<double>(photo.cols) / std::max(crop_w, 1),
                               static_cast<double>(photo.rows) / std::max(crop_h, 1)));
    crop_w = std::max(4, static_cast<int>(crop_w * fit));
    crop_h = std::max(4, static_cast<int>(crop_h * fit));
    const cv::Rect crop(rng.UniformInt(0, photo.cols - crop_w),
                        rng.UniformInt(0, photo.rows - crop_h), crop_w, crop_h);
    cv::Mat patch = photo(crop).clone();
    if (quarter_turns > 0) {
      static const cv::RotateFlags kTurns[] = {cv::ROTATE_90_CLOCKWISE, cv::ROTATE_180,
                                               cv::ROTATE_90_COUNTERCLOCKWISE};
      cv::rotate(patch, patch, kTurns[quarter_turns - 1]);
    }
    if (mirror) cv::flip(patch, patch, 1);
    cv::Mat resized;
    cv::resize(patch, resized, cv::Size(width, height), 0, 0,
               width < patch.cols ? cv::INTER_AREA : cv::INTER_LINEAR);
    const float gain = static_cast<float>(rng.Uniform(0.8, 1.2));
    const auto channel = [&] { return gain * static_cast<float>(rng.Uniform(0.85, 1.15)); };
    const auto offset = [&] { return static_cast<float>(rng.Uniform(-20, 20)); };
    const float b_gain = channel(), b_offset = offset(), g_gain = channel(), g_offset = offset(),
                r_gain = channel(), r_offset = offset();
    const cv::Matx34f cast(b_gain, 0, 0, b_offset, 0, g_gain, 0, g_offset, 0, 0, r_gain, r_offset);
    cv::transform(resized, resized, cast);
    return resized;
  }

  // A printed page: text rows in a few sizes, sometimes a figure (photo or chart).
  cv::Mat Document(int width, int height) {
    const double paper = rng.Uniform(215.0, 250.0);
    const double blue_shift = rng.Uniform(0.0, 25.0);
    const double green_shift = rng.Uniform(0.0, 10.0);
    cv::Mat page(height, width, CV_8UC3,
                 cv::Scalar(paper - blue_shift, paper - green_shift, paper));
    const cv::Scalar ink = rng.Chance(0.8) ? cv::Scalar(30, 25, 25) : RandomColour(0.1, 0.5);
    const double margin = 0.08 * width;
    const double line = std::max(4.0, height / rng.Uniform(18.0, 40.0));
    double y = margin + line;
    while (y < height - margin) {
      const double roll = rng.Uniform();
      if (roll < 0.12 && y + 6 * line < height - margin) {
        const int fw = std::max(4, static_cast<int>(rng.Uniform(0.4, 0.85) * (width - 2 * margin)));
        const int fh = std::max(4, static_cast<int>(rng.Uniform(3.0, 6.0) * line));
        const cv::Rect box(static_cast<int>(margin), static_cast<int>(y - line), fw, fh);
        const cv::Rect inside = box & cv::Rect(0, 0, width, height);
        if (!photos.Empty() && rng.Chance(0.6)) {
          const cv::Mat figure = PhotoPatch(fw, fh);
          figure(cv::Rect(0, 0, inside.width, inside.height)).copyTo(page(inside));
        } else {
          cv::rectangle(page, box, ink, 1, cv::LINE_AA);
          std::vector<cv::Point> curve;
          for (int k = 0; k <= 12; ++k) {
            curve.push_back(
                Fixed(box.x + box.width * k / 12.0, box.y + box.height * rng.Uniform(0.15, 0.85)));
          }
          cv::polylines(page, curve, false, RandomColour(0.2, 0.8), 1, cv::LINE_AA, 3);
        }
        y += fh + line;
        continue;
      }
      const bool heading = roll < 0.22;
      const double text_size = heading ? 1.6 * line : line;
      double x = margin + (roll < 0.3 ? line : 0.0);
      const double right = width - margin - rng.Uniform(0.0, 0.3) * width;
      while (x < right) {
        const int letters = rng.UniformInt(1, 9);
        std::string word;
        for (int k = 0; k < letters; ++k) word += static_cast<char>('a' + rng.UniformInt(0, 25));
        const double scale = std::max(0.12, 0.7 * text_size / 22.0);
        int baseline = 0;
        const cv::Size extent =
            cv::getTextSize(word, cv::FONT_HERSHEY_SIMPLEX, scale, heading ? 2 : 1, &baseline);
        if (x + extent.width > right) break;
        cv::putText(page, word, cv::Point(static_cast<int>(x), static_cast<int>(y)),
                    cv::FONT_HERSHEY_SIMPLEX, scale, ink, heading ? 2 : 1, cv::LINE_AA);
        x += extent.width + 0.5 * text_size;
      }
      y += text_size * 1.5;
    }
    return page;
  }

  // Pastes `patch` centred at `centre`, turned by `angle_deg`, optionally framed.
  void Paste(cv::Mat* image, const cv::Mat& patch, const cv::Point2d& centre, double angle_deg,
             bool frame) {
    cv::Mat framed = patch;
    if (frame) {
      framed = patch.clone();
      const cv::Scalar colour = rng.Chance(0.5) ? RandomColour(0.0, 0.3) : RandomColour(0.75, 1.0);
      const int thickness =
          std::max(1, static_cast<int>(std::lround(Px(rng.Uniform(0.004, 0.012)))));
      cv::rectangle(framed, cv::Rect(0, 0, framed.cols, framed.rows), colour, 2 * thickness);
    }
    // Warp only into the bounding box of the turned patch.
    const cv::RotatedRect turned(
        cv::Point2f(static_cast<float>(centre.x), static_cast<float>(centre.y)),
        cv::Size2f(static_cast<float>(framed.cols), static_cast<float>(framed.rows)),
        static_cast<float>(angle_deg));
    const cv::Rect box = turned.boundingRect() & cv::Rect(0, 0, image->cols, image->rows);
    if (box.empty()) return;
    cv::Mat M = cv::getRotationMatrix2D(cv::Point2f(0.5f * framed.cols, 0.5f * framed.rows),
                                        -angle_deg, 1.0);
    M.at<double>(0, 2) += centre.x - 0.5 * framed.cols - box.x;
    M.at<double>(1, 2) += centre.y - 0.5 * framed.rows - box.y;
    cv::Mat region = (*image)(box);
    cv::warpAffine(framed, region, M, box.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  }
};

}  // namespace drvslam::synth::painting
