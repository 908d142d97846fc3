#include "drvslam/tools/synth/shutter_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>

namespace drvslam::synth {
namespace {

const CameraOptions& CheckedSensor(const CameraOptions& sensor, const RealCameraOptions& options) {
  options.Check();
  sensor.Check();
  return sensor;
}

// First row of band `band` of `bands` over `height` rows.
int BandStart(int band, int bands, int height) {
  return static_cast<int>(static_cast<long long>(band) * height / bands);
}

// Bilinear lookup in a 3-channel float image; (x, y) lie inside it, with margin, by
// construction of the canvas, but float rounding may touch the last column or row.
void SampleBilinear(const cv::Mat& image, float x, float y, float out[3]) {
  const int x0 = std::min(static_cast<int>(x), image.cols - 2);
  const int y0 = std::min(static_cast<int>(y), image.rows - 2);
  const float fx = std::min(1.0f, x - x0), fy = std::min(1.0f, y - y0);
  const float* a = image.ptr<float>(y0) + 3 * x0;
  const float* c = image.ptr<float>(y0 + 1) + 3 * x0;
  for (int k = 0; k < 3; ++k) {
    const float top = a[k] + fx * (a[3 + k] - a[k]);
    const float bottom = c[k] + fx * (c[3 + k] - c[k]);
    out[k] = top + fy * (bottom - top);
  }
}

uint8_t ToByte(float value) {
  return static_cast<uint8_t>(std::min(255.0f, std::max(0.0f, value + 0.5f)));
}

}  // namespace

ShutterRenderer::ShutterRenderer(const CameraOptions& sensor, const RealCameraOptions& options,
                                 const RasterOptions& raster)
    : sensor_(CheckedSensor(sensor, options)),
      options_(options),
      distortion_(sensor),
      rasterizer_(distortion_.Canvas(), raster) {
  bands_ = options_.RollingShutter() ? std::min(options_.rolling_shutter_steps, sensor_.height) : 1;
  if (options_.Blur()) {
    const int n = options_.blur_samples;
    for (int i = 0; i < n; ++i) {
      sample_offsets_.push_back(((i + 0.5) / n - 0.5) * options_.blur_exposure);
    }
    // The midpoint rule puts a sample exactly at the centre when n is odd.
    centre_sample_ = n % 2 == 1 ? n / 2 : -1;
  } else {
    sample_offsets_ = {0.0};
    centre_sample_ = 0;
  }
}

bool ShutterRenderer::SingleRender() const {
  return bands_ == 1 && sample_offsets_.size() == 1 && distortion_.Identity();
}

double ShutterRenderer::RowOffset(int row) const {
  if (!options_.RollingShutter()) return 0.0;
  const int height = sensor_.height;
  // The last band starting at or before `row`: BandStart(b) <= row < BandStart(b + 1).
  const long long rows = static_cast<long long>(std::clamp(row, 0, height - 1)) + 1;
  const int band = static_cast<int>((rows * bands_ + height - 1) / height) - 1;
  const double middle =
      0.5 * (BandStart(band, bands_, height) + BandStart(band + 1, bands_, height));
  return (middle / height - 0.5) * options_.rolling_shutter_readout;
}

void ShutterRenderer::Render(const TriangleList& statics, const std::vector<Texture>& textures,
                             const SceneAt& scene_at, RenderBuffers* out) const {
  const int width = sensor_.width, height = sensor_.height;
  if (SingleRender()) {
    SE3 T_cw;
    TriangleList movers;
    scene_at(0.0, &T_cw, &movers);
    rasterizer_.Render({&statics, &movers}, textures, T_cw, out);
    return;
  }
  out->bgr.create(height, width, CV_8UC3);
  out->depth.create(height, width, CV_32FC1);
  out->instance.create(height, width, CV_16UC1);
  out->incidence.create(height, width, CV_32FC1);
  if (bands_ == 1) {
    RenderBand(0, height, 0.0, statics, textures, scene_at, /*parallel=*/true, out);
    return;
  }
  cv::parallel_for_(cv::Range(0, bands_), [&](const cv::Range& range) {
    for (int band = range.start; band < range.end; ++band) {
      const int row_begin = BandStart(band, bands_, height);
      const int row_end = BandStart(band + 1, bands_, height);
      if (row_begin >= row_end) continue;
      RenderBand(row_begin, row_end, RowOffset(row_begin), statics, textures, scene_at,
                 /*parallel=*/false, out);
    }
  });
  if (options_.depth_global_shutter) RenderGlobalDepth(statics, textures, scene_at, out);
}

void ShutterRenderer::RenderGlobalDepth(const TriangleList& statics,
                                        const std::vector<Texture>& textures,
                                        const SceneAt& scene_at, RenderBuffers* out) const {
  SE3 T_cw;
  TriangleList movers;
  scene_at(0.0, &T_cw, &movers);
  RenderBuffers canvas;
  rasterizer_.Render({&statics, &movers}, textures, T_cw, &canvas);
  if (distortion_.Identity()) {
    canvas.depth.copyTo(out->depth);
    canvas.incidence.copyTo(out->incidence);
    return;
  }
  const CameraOptions& canvas_camera = distortion_.Canvas();
  cv::parallel_for_(cv::Range(0, sensor_.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      float* depth_row = out->depth.ptr<float>(y);
      float* incidence_row = out->incidence.ptr<float>(y);
      for (int x = 0; x < sensor_.width; ++x) {
        const int source_x = std::min(static_cast<int>(std::lround(distortion_.CanvasX(x, y))),
                                      canvas_camera.width - 1);
        const int source_y = std::min(static_cast<int>(std::lround(distortion_.CanvasY(x, y))),
                                      canvas_camera.height - 1);
        depth_row[x] = canvas.depth.ptr<float>(source_y)[source_x];
        incidence_row[x] = canvas.incidence.ptr<float>(source_y)[source_x];
      }
    }
  });
}

void ShutterRenderer::RenderBand(int row_begin, int row_end, double offset,
                                 const TriangleList& statics, const std::vector<Texture>& textures,
                                 const SceneAt& scene_at, bool parallel, RenderBuffers* out) const {
  // Named variables, not a structured binding: C++17 lambdas may not capture those.
  const std::pair<int, int> canvas_rows = distortion_.CanvasRows(row_begin, row_end);
  const int canvas_begin = canvas_rows.first;
  const int canvas_end = canvas_rows.second;
  const int canvas_width = distortion_.Canvas().width;
  const auto render_at = [&](double time_offset, RenderBuffers* buffers) {
    SE3 T_cw;
    TriangleList movers;
    scene_at(time_offset, &T_cw, &movers);
    rasterizer_.RenderRows({&statics, &movers}, textures, T_cw, canvas_begin, canvas_end, buffers,
                           parallel);
  };

  // Colour: the sum of the samples, in canvas rows [canvas_begin, canvas_end).
  cv::Mat colour_sum(canvas_end - canvas_begin, canvas_width, CV_32FC3, cv::Scalar::all(0));
  RenderBuffers sample, centre;
  for (int i = 0; i < static_cast<int>(sample_offsets_.size()); ++i) {
    render_at(offset + sample_offsets_[i], &sample);
    cv::accumulate(sample.bgr, colour_sum);
    if (i == centre_sample_) std::swap(sample, centre);
  }
  if (centre_sample_ < 0) render_at(offset, &centre);
  const float inverse_count = 1.0f / static_cast<float>(sample_offsets_.size());

  const auto assemble_rows = [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      uint8_t* bgr_row = out->bgr.ptr<uint8_t>(y);
      float* depth_row = out->depth.ptr<float>(y);
      uint16_t* id_row = out->instance.ptr<uint16_t>(y);
      float* incidence_row = out->incidence.ptr<float>(y);
      for (int x = 0; x < sensor_.width; ++x) {
        float colour[3];
        // The canvas pixel whose depth and instance id this pixel takes.
        int source_x = x, source_y = y - canvas_begin;
        if (distortion_.Identity()) {
          const float* sum = colour_sum.ptr<float>(source_y) + 3 * x;
          for (int k = 0; k < 3; ++k) colour[k] = sum[k];
        } else {
          const float u = distortion_.CanvasX(x, y);
          const float v = distortion_.CanvasY(x, y) - static_cast<float>(canvas_begin);
          SampleBilinear(colour_sum, u, v, colour);
          source_x = std::min(static_cast<int>(std::lround(u)), canvas_width - 1);
          source_y = std::min(static_cast<int>(std::lround(v)), canvas_end - canvas_begin - 1);
        }
        for (int k = 0; k < 3; ++k) bgr_row[3 * x + k] = ToByte(colour[k] * inverse_count);
        depth_row[x] = centre.depth.ptr<float>(source_y)[source_x];
        id_row[x] = centre.instance.ptr<uint16_t>(source_y)[source_x];
        incidence_row[x] = centre.incidence.ptr<float>(source_y)[source_x];
      }
    }
  };
  if (parallel) {
    cv::parallel_for_(cv::Range(row_begin, row_end), assemble_rows);
  } else {
    assemble_rows(cv::Range(row_begin, row_end));
  }
}

}  // namespace drvslam::synth
