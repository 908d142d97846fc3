// Texture painting: turns a request (physical size, texel density, style, seed) into an image.
// Every surface gets its own texture painted for its size, so nothing repeats across the room;
// detail spans several scales (from centimetre glyphs to half-metre photo patches) so ORB finds
// distinctive corners at every pyramid level and viewing distance.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "drvslam/tools/synth/photo_library.h"

namespace drvslam::synth {

enum class TextureStyle {
  kCollage,     // posters, photos and pages on plaster (painted posters without photos)
  kProcedural,  // multi-scale noise under random shapes, strokes and glyphs
  kCloth,       // a dominant colour with folds, irregular stripes and prints
  kSkin,        // skin tone with fine detail; hair and a face when face_rect is set
  kKeyboard,    // rows of keys with letters
  kLabel,       // packaging and book covers: a strong colour, large glyphs and shapes
  kPlaster,     // a light wall or ceiling with dense marks, stains and scribbles
  kWood,        // furniture: wood grain, knots, scratches and stickers
  kDesk,        // a desk top: wood under papers, pages and photographs
};

struct TextureRequest {
  double width_m = 1.0;
  double height_m = 1.0;
  double texels_per_metre = 320.0;
  // Longest side in texels; a larger surface gets a proportionally lower density.
  int max_side = 2048;
  TextureStyle style = TextureStyle::kCollage;
  uint32_t seed = 0;
  cv::Vec3b colour{128, 128, 128};  // dominant colour (BGR) of cloth, skin and labels
  // kSkin: the face, in normalized texture coordinates; hair covers the rest. Empty: no hair.
  cv::Rect2d face_rect;
  // Final tone: saturation (0 grey .. 1 as painted) and brightness gain, e.g. to make a floor
  // read as a darker carpet. Luminance contrast, which features need, is kept.
  double saturation = 1.0;
  double brightness = 1.0;

  // The image size this request paints (each side at least 8 texels).
  cv::Size PixelSize() const;
};

// Paints the request as a CV_8UC3 BGR image. Deterministic: the same request and photos give
// the same image.
cv::Mat PaintTexture(const TextureRequest& request, const PhotoLibrary& photos);

}  // namespace drvslam::synth
