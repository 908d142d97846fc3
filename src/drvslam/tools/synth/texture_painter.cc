#include "drvslam/tools/synth/texture_painter.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/tools/synth/random.h"
#include "drvslam/tools/synth/texture_brushes.h"

namespace drvslam::synth {
namespace {

using painting::Octave;
using painting::TextureBrushes;

// The styles, each composed from the brushes.
struct Painter : TextureBrushes {
  using TextureBrushes::TextureBrushes;

  // Light plaster: gentle luminance variation with marks, stains and scribbles at many scales.
  cv::Mat Plaster(double marks_per_m2) {
    const double light = rng.Uniform(175.0, 230.0);
    const cv::Scalar base = cv::Scalar(light, light, light) * 0.85 + RandomColour(0.0, 1.0) * 0.15;
    cv::Mat image = NoiseImage(base, {{0.5, 25.0, false}, {0.1, 15.0, false}, {0.02, 10.0, false}});
    std::vector<cv::Scalar> palette;
    for (int k = 0; k < 6; ++k) palette.push_back(RandomColour(0.0, 0.6));
    DrawShapes(&image, PerArea(marks_per_m2), 0.004, 0.08, palette);
    DrawGlyphRuns(&image, PerArea(0.3 * marks_per_m2), 0.01, 0.05, palette);
    return image;
  }

  cv::Mat Procedural(double shapes_per_m2) {
    // A muted background with mostly luminance structure, under saturated shapes.
    const double grey = rng.Uniform(70.0, 190.0);
    const cv::Scalar tint = RandomColour(0.0, 1.0) * 0.3;
    const cv::Scalar base = cv::Scalar(grey, grey, grey) * 0.7 + tint;
    cv::Mat image = NoiseImage(base, {{0.5, 45.0, false},
                                      {0.5, 18.0, true},
                                      {0.12, 30.0, false},
                                      {0.12, 12.0, true},
                                      {0.03, 25.0, false},
                                      {0.008, 12.0, false}});
    DrawShapes(&image, PerArea(shapes_per_m2), 0.012, 0.35);
    DrawGlyphRuns(&image, PerArea(0.15 * shapes_per_m2), 0.015, 0.12);
    AddGrain(&image, 8.0);
    return image;
  }

  // A painted poster of w x h texels (for walls without photographs).
  cv::Mat PaintedPatch(int width, int height) {
    Painter inner(request, photos);
    inner.rng = Random(rng.Bits());
    inner.size = cv::Size(width, height);
    inner.area_m2 = (width / density) * (height / density);
    return inner.Procedural(200.0);
  }

  // Walls: posters, photographs and printed pages on plaster. Without photographs the posters
  // are painted.
  cv::Mat Collage() {
    cv::Mat image = Plaster(150.0);
    const double cell = Px(0.45);
    const int cols = std::max(1, static_cast<int>(std::ceil(size.width / cell)));
    const int rows = std::max(1, static_cast<int>(std::ceil(size.height / cell)));
    for (int gy = 0; gy < rows; ++gy) {
      for (int gx = 0; gx < cols; ++gx) {
        if (!rng.Chance(0.85)) continue;
        const int w = std::max(8, static_cast<int>(Px(rng.Uniform(0.25, 0.6))));
        const int h = std::max(8, static_cast<int>(w * rng.Uniform(0.7, 1.45)));
        const cv::Point2d centre((gx + 0.5) * cell + Px(rng.Uniform(-0.12, 0.12)),
                                 (gy + 0.5) * cell + Px(rng.Uniform(-0.12, 0.12)));
        const double kind = rng.Uniform();
        const cv::Mat patch = !photos.Empty() && kind < 0.7 ? PhotoPatch(w, h)
                              : kind < 0.85                 ? Document(w, h)
                                                            : PaintedPatch(w, h);
        const double angle = rng.Chance(0.7) ? 0.0 : rng.Uniform(-12.0, 12.0);
        Paste(&image, patch, centre, angle, rng.Chance(0.7));
      }
    }
    DrawShapes(&image, PerArea(30.0), 0.008, 0.04);
    AddGrain(&image, 5.0);
    return image;
  }

  // Adds anisotropic noise (cells of `along` by `across` metres) to a one-channel image.
  void AddGrainLines(cv::Mat* target, double along, double across, double amplitude) {
    const double cell_x = std::max(1.0, Px(along)), cell_y = std::max(1.0, Px(across));
    const int gw = static_cast<int>(std::ceil(size.width / cell_x)) + 2;
    const int gh = static_cast<int>(std::ceil(size.height / cell_y)) + 2;
    cv::Mat grid(gh, gw, CV_32FC1);
    cv::RNG fill_rng(rng.Bits64());
    fill_rng.fill(grid, cv::RNG::UNIFORM, -amplitude, amplitude);
    cv::Mat up;
    cv::resize(grid, up, cv::Size(static_cast<int>(gw * cell_x), static_cast<int>(gh * cell_y)), 0,
               0, cv::INTER_CUBIC);
    *target += up(cv::Rect(0, 0, size.width, size.height));
  }

  // Wood: grain along x, knots, scratches and the odd sticker.
  cv::Mat Wood() {
    static const cv::Scalar kTones[] = {
        {110, 165, 210}, {65, 105, 155}, {40, 60, 95}, {50, 75, 140}, {150, 180, 200}};
    const cv::Scalar base = kTones[rng.UniformInt(0, 4)] * rng.Uniform(0.85, 1.15);
    cv::Mat grain(size, CV_32FC1, cv::Scalar(0.0));
    AddGrainLines(&grain, 0.5, 0.006, 30.0);
    AddGrainLines(&grain, 0.15, 0.002, 16.0);
    grain += OctaveImage({0.08, 12.0, false});
    cv::Mat colour(size, CV_32FC3, base);
    cv::Mat spread;
    cv::cvtColor(grain, spread, cv::COLOR_GRAY2BGR);
    colour += spread;
    cv::Mat image;
    colour.convertTo(image, CV_8UC3);
    for (int k = PerArea(4.0); k > 0; --k) {
      const cv::Point centre = Fixed(rng.Uniform(0, size.width), rng.Uniform(0, size.height));
      const double r = Px(rng.Uniform(0.006, 0.02));
      cv::ellipse(image, centre, cv::Size(static_cast<int>(r * 8 * 2.5), static_cast<int>(r * 8)),
                  rng.Uniform(-10.0, 10.0), 0, 360, base * 0.45, cv::FILLED, cv::LINE_AA, 3);
      cv::ellipse(image, centre,
                  cv::Size(static_cast<int>(r * 8 * 4.0), static_cast<int>(r * 8 * 1.8)), 0, 0, 360,
                  base * 0.6, 1, cv::LINE_AA, 3);
    }
    const std::vector<cv::Scalar> marks = {base * 0.4, base * 0.6, base * 1.3,
                                           cv::Scalar(235, 235, 235)};
    DrawShapes(&image, PerArea(70.0), 0.004, 0.03, marks);
    DrawShapes(&image, PerArea(8.0), 0.01, 0.05);  // stickers
    DrawGlyphRuns(&image, PerArea(6.0), 0.01, 0.03, marks);
    AddGrain(&image, 6.0);
    return image;
  }

  // A desk top: wood under papers, magazines and notes.
  cv::Mat Desk() {
    cv::Mat image = Wood();
    for (int k = std::max(2, PerArea(9.0)); k > 0; --k) {
      const double scale = rng.Uniform(0.55, 1.0);
      const int w = std::max(8, static_cast<int>(Px(0.21 * scale)));
      const int h = std::max(8, static_cast<int>(Px(0.297 * scale)));
      const cv::Mat patch = !photos.Empty() && rng.Chance(0.35) ? PhotoPatch(w, h) : Document(w, h);
      const cv::Point2d centre(rng.Uniform(0, size.width), rng.Uniform(0, size.height));
      Paste(&image, patch, centre, rng.Uniform(-35.0, 35.0), false);
    }
    DrawShapes(&image, PerArea(25.0), 0.005, 0.04);
    AddGrain(&image, 5.0);
    return image;
  }

  cv::Mat Cloth() {
    const cv::Scalar base(request.colour[0], request.colour[1], request.colour[2]);
    cv::Mat image =
        NoiseImage(base, {{0.25, 30.0, false}, {0.06, 20.0, true}, {0.015, 10.0, false}});
    const cv::Scalar accent = Contrasting(base);
    if (rng.Chance(0.6)) {
      // Irregular stripes: random widths and gaps, so the pattern never repeats exactly.
      const double angle = rng.Pick(std::vector<double>{0.0, 90.0, 45.0, -45.0}) * M_PI / 180.0;
      const double diagonal = std::hypot(size.width, size.height);
      const cv::Point2d along(std::cos(angle), std::sin(angle));
      const cv::Point2d across(-along.y, along.x);
      const cv::Point2d centre(0.5 * size.width, 0.5 * size.height);
      for (double offset = -0.5 * diagonal; offset < 0.5 * diagonal;) {
        const double width = Px(rng.LogUniform(0.004, 0.03));
        const cv::Point2d mid = centre + across * (offset + 0.5 * width);
        cv::line(image, Fixed(mid.x - along.x * diagonal, mid.y - along.y * diagonal),
                 Fixed(mid.x + along.x * diagonal, mid.y + along.y * diagonal), accent,
                 std::max(1, static_cast<int>(std::lround(width))), cv::LINE_AA, 3);
        offset += width + Px(rng.LogUniform(0.01, 0.08));
      }
    }
    const std::vector<cv::Scalar> palette = {accent, Contrasting(base), RandomColour()};
    DrawShapes(&image, PerArea(120.0), 0.008, 0.08, palette);
    DrawGlyphRuns(&image, PerArea(10.0), 0.01, 0.05, palette);
    AddGrain(&image, 14.0);
    return image;
  }

  cv::Mat Skin() {
    const cv::Scalar base(request.colour[0], request.colour[1], request.colour[2]);
    cv::Mat image = NoiseImage(base, {{0.1, 12.0, true}, {0.02, 10.0, false}});
    const cv::Scalar darker = base * 0.8;
    DrawShapes(&image, PerArea(150.0), 0.003, 0.015, {darker, base * 0.9});
    if (!request.face_rect.empty()) {
      const cv::Rect face(static_cast<int>(request.face_rect.x * size.width),
                          static_cast<int>(request.face_rect.y * size.height),
                          static_cast<int>(request.face_rect.width * size.width),
                          static_cast<int>(request.face_rect.height * size.height));
      // Hair everywhere but the lower three quarters of the face.
      const cv::Scalar hair = RandomColour(0.05, 0.45, 0.2);
      cv::Mat hair_layer = NoiseImage(hair, {{0.03, 25.0, false}, {0.005, 20.0, false}});
      for (int k = 0; k < PerArea(3000.0); ++k) {
        const double x = rng.Uniform(0, size.width), y = rng.Uniform(0, size.height);
        const double angle = rng.Uniform(1.2, 1.9), length = Px(rng.Uniform(0.01, 0.05));
        cv::line(hair_layer, Fixed(x, y),
                 Fixed(x + length * std::cos(angle), y + length * std::sin(angle)),
                 rng.Chance(0.5) ? hair * 0.6 : hair * 1.5, 1, cv::LINE_AA, 3);
      }
      cv::Mat hair_mask(size, CV_8UC1, cv::Scalar(255));
      const int top = face.y + face.height / 4;
      hair_mask(cv::Rect(face.x, top, face.width, face.y + face.height - top) &
                cv::Rect(0, 0, size.width, size.height))
          .setTo(0);
      hair_layer.copyTo(image, hair_mask);
      const auto at = [&](double fx, double fy) {
        return Fixed(face.x + fx * face.width, face.y + fy * face.height);
      };
      const int unit = std::max(1, face.width / 10);
      for (const double fx : {0.3, 0.7}) {
        cv::ellipse(image, at(fx, 0.45), cv::Size(unit * 8 * 3 / 2, unit * 8 * 3 / 4), 0, 0, 360,
                    cv::Scalar(240, 240, 240), cv::FILLED, cv::LINE_AA, 3);
        cv::circle(image, at(fx + rng.Uniform(-0.02, 0.02), 0.45), unit * 8 * 2 / 3,
                   cv::Scalar(60, 40, 20), cv::FILLED, cv::LINE_AA, 3);
        cv::line(image, at(fx - 0.12, 0.35), at(fx + 0.12, 0.34), hair * 0.7, std::max(1, unit / 2),
                 cv::LINE_AA, 3);
      }
      cv::line(image, at(0.5, 0.5), at(0.47, 0.65), darker * 0.8, std::max(1, unit / 3),
               cv::LINE_AA, 3);
      cv::ellipse(image, at(0.5, 0.78), cv::Size(unit * 8 * 2, unit * 8 / 2), 0, 0, 360,
                  cv::Scalar(70, 60, 170), cv::FILLED, cv::LINE_AA, 3);
    }
    AddGrain(&image, 6.0);
    return image;
  }

  cv::Mat Keyboard() {
    cv::Mat image = NoiseImage(cv::Scalar(40, 40, 42), {{0.05, 8.0, false}});
    const int rows = 5;
    const double pitch_y = static_cast<double>(size.height) / (rows + 0.4);
    const double pitch_x = static_cast<double>(size.width) / 15.5;
    for (int row = 0; row < rows; ++row) {
      double x = pitch_x * (0.2 + 0.25 * row);
      const double y = pitch_y * (0.2 + row);
      while (x < size.width - pitch_x * 0.8) {
        const double width = pitch_x * (rng.Chance(0.12) ? rng.Uniform(1.4, 2.2) : 1.0);
        const double shade = rng.Uniform(180.0, 225.0);
        const cv::Scalar key(shade, shade, shade + rng.Uniform(-8.0, 8.0));
        cv::rectangle(image, Fixed(x + 0.08 * pitch_x, y + 0.08 * pitch_y),
                      Fixed(x + width - 0.08 * pitch_x, y + 0.92 * pitch_y), key, cv::FILLED,
                      cv::LINE_AA, 3);
        static const char kKeys[] = "QWERTYUIOPASDFGHJKLZXCVBNM1234567890";
        const std::string label(1, kKeys[rng.UniformInt(0, static_cast<int>(sizeof(kKeys)) - 2)]);
        const double scale = std::max(0.15, 0.45 * pitch_y / 22.0);
        cv::putText(
            image, label,
            cv::Point(static_cast<int>(x + 0.25 * pitch_x), static_cast<int>(y + 0.7 * pitch_y)),
            cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(30, 30, 30),
            std::max(1, static_cast<int>(scale * 1.5)), cv::LINE_AA);
        x += width;
      }
    }
    AddGrain(&image, 6.0);
    return image;
  }

  cv::Mat Label() {
    const cv::Scalar base(request.colour[0], request.colour[1], request.colour[2]);
    cv::Mat image = NoiseImage(base, {{0.1, 25.0, true}, {0.02, 12.0, false}});
    const cv::Scalar accent = Contrasting(base);
    for (int band = rng.UniformInt(1, 3); band > 0; --band) {
      const double y = rng.Uniform(0.0, size.height);
      const double h = rng.Uniform(0.04, 0.2) * size.height;
      cv::rectangle(image, Fixed(0, y), Fixed(size.width, y + h),
                    rng.Chance(0.5) ? accent : RandomColour(), cv::FILLED, cv::LINE_AA, 3);
    }
    const std::vector<cv::Scalar> palette = {accent, Contrasting(base), RandomColour()};
    DrawShapes(&image, PerArea(200.0), 0.005, 0.05, palette);
    for (int k = rng.UniformInt(2, 4); k > 0; --k) {
      DrawGlyphs(&image, rng.Uniform(0.08, 0.25) * std::min(size.width, size.height),
                 rng.Pick(palette), rng.UniformInt(3, 10));
    }
    DrawGlyphRuns(&image, PerArea(150.0), 0.004, 0.02, palette);
    AddGrain(&image, 8.0);
    return image;
  }
};

}  // namespace

cv::Size TextureRequest::PixelSize() const {
  double w = std::max(width_m, 0.0) * texels_per_metre;
  double h = std::max(height_m, 0.0) * texels_per_metre;
  const double longest = std::max(w, h);
  if (longest > max_side) {
    w *= max_side / longest;
    h *= max_side / longest;
  }
  return cv::Size(std::max(8, static_cast<int>(std::lround(w))),
                  std::max(8, static_cast<int>(std::lround(h))));
}

cv::Mat PaintTexture(const TextureRequest& request, const PhotoLibrary& photos) {
  Painter painter(request, photos);
  cv::Mat image;
  switch (request.style) {
    case TextureStyle::kCollage:
      image = painter.Collage();
      break;
    case TextureStyle::kProcedural:
      image = painter.Procedural(160.0);
      break;
    case TextureStyle::kCloth:
      image = painter.Cloth();
      break;
    case TextureStyle::kSkin:
      image = painter.Skin();
      break;
    case TextureStyle::kKeyboard:
      image = painter.Keyboard();
      break;
    case TextureStyle::kLabel:
      image = painter.Label();
      break;
    case TextureStyle::kPlaster:
      image = painter.Plaster(400.0);
      break;
    case TextureStyle::kWood:
      image = painter.Wood();
      break;
    case TextureStyle::kDesk:
      image = painter.Desk();
      break;
  }
  if (request.saturation != 1.0 || request.brightness != 1.0) {
    const float saturation = static_cast<float>(request.saturation);
    const float brightness = static_cast<float>(request.brightness);
    for (int y = 0; y < image.rows; ++y) {
      uint8_t* row = image.ptr<uint8_t>(y);
      for (int x = 0; x < image.cols; ++x) {
        uint8_t* p = row + 3 * x;
        const float grey = 0.114f * p[0] + 0.587f * p[1] + 0.299f * p[2];
        for (int c = 0; c < 3; ++c) {
          const float value = (grey + (p[c] - grey) * saturation) * brightness + 0.5f;
          p[c] = static_cast<uint8_t>(std::min(255.0f, std::max(0.0f, value)));
        }
      }
    }
  }
  return image;
}

}  // namespace drvslam::synth
