#include "drvslam/tools/synth/texture_bank.h"

#include <opencv2/core/utility.hpp>
#include <optional>

namespace drvslam::synth {

int TextureBank::Add(const TextureRequest& request) {
  TextureRequest scaled = request;
  scaled.texels_per_metre *= density_scale_;
  entries_.push_back({scaled, cv::Mat()});
  return static_cast<int>(entries_.size()) - 1;
}

int TextureBank::AddImage(const cv::Mat& image) {
  entries_.push_back({TextureRequest(), image});
  return static_cast<int>(entries_.size()) - 1;
}

long long TextureBank::TexelCount() const {
  long long total = 0;
  for (const Entry& entry : entries_) {
    const cv::Size size = entry.image.empty() ? entry.request.PixelSize() : entry.image.size();
    total += static_cast<long long>(size.width) * size.height;
  }
  return total;
}

std::vector<Texture> TextureBank::Realize(const PhotoLibrary& photos) const {
  std::vector<std::optional<Texture>> painted(entries_.size());
  cv::parallel_for_(cv::Range(0, static_cast<int>(entries_.size())), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      const Entry& entry = entries_[i];
      painted[i].emplace(entry.image.empty() ? PaintTexture(entry.request, photos) : entry.image);
    }
  });
  std::vector<Texture> textures;
  textures.reserve(painted.size());
  for (std::optional<Texture>& texture : painted) textures.push_back(std::move(*texture));
  return textures;
}

}  // namespace drvslam::synth
