// TextureBank: collects the textures a scene needs while its geometry is built (a triangle
// only needs the id Add() returns), then paints them all at once. Each texture depends only on
// its own request (which carries its own seed), so painting them in parallel, in any order,
// gives the same images.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/tools/synth/photo_library.h"
#include "drvslam/tools/synth/texture.h"
#include "drvslam/tools/synth/texture_painter.h"

namespace drvslam::synth {

class TextureBank {
 public:
  // Painted textures get density_scale times the texel density they ask for: the generator
  // passes the image width over 640, so that texels stay about as large as pixels.
  explicit TextureBank(double density_scale = 1.0) : density_scale_(density_scale) {}

  // Returns the texture id triangles use.
  int Add(const TextureRequest& request);
  // A ready-made image (a billboard cut-out), BGR or BGRA.
  int AddImage(const cv::Mat& image);
  int Size() const { return static_cast<int>(entries_.size()); }
  // Total texels that Realize() will paint (for logging the cost).
  long long TexelCount() const;

  std::vector<Texture> Realize(const PhotoLibrary& photos) const;

 private:
  struct Entry {
    TextureRequest request;
    cv::Mat image;  // set for ready-made images
  };
  double density_scale_;
  std::vector<Entry> entries_;
};

}  // namespace drvslam::synth
