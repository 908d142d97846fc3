#include "drvslam/tools/synth/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core/utility.hpp>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/tools/synth/hash_noise.h"

namespace drvslam::synth {
namespace {

constexpr int kNoiseBands = 16;

void RequireSensorSetting(bool ok, const char* name, double value, const char* rule) {
  if (ok) return;
  std::ostringstream message;
  message << "sensor." << name << " = " << value << " " << rule;
  throw Error(message.str());
}

bool FiniteWithin(double value, double lo, double hi) {
  return std::isfinite(value) && value >= lo && value <= hi;
}

// Bilinear colour lookup with the coordinates clamped to the image.
void SampleColour(const cv::Mat& image, float x, float y, float out[3]) {
  x = std::min(std::max(x, 0.0f), image.cols - 1.0f);
  y = std::min(std::max(y, 0.0f), image.rows - 1.0f);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, image.cols - 1), y1 = std::min(y0 + 1, image.rows - 1);
  const float fx = x - x0, fy = y - y0;
  const uint8_t* a = image.ptr<uint8_t>(y0) + 3 * x0;
  const uint8_t* b = image.ptr<uint8_t>(y0) + 3 * x1;
  const uint8_t* c = image.ptr<uint8_t>(y1) + 3 * x0;
  const uint8_t* d = image.ptr<uint8_t>(y1) + 3 * x1;
  for (int k = 0; k < 3; ++k) {
    out[k] =
        (1 - fx) * (1 - fy) * a[k] + fx * (1 - fy) * b[k] + (1 - fx) * fy * c[k] + fx * fy * d[k];
  }
}

}  // namespace

SensorOptions SensorOptions::Clean() {
  SensorOptions options;
  options.depth_noise = false;
  options.depth_quantization = false;
  options.edge_holes = false;
  options.grazing_holes = false;
  options.range_limits = false;
  options.color_noise = false;
  options.exposure = false;
  options.motion_blur = false;
  return options;
}

void SensorOptions::Check() const {
  RequireSensorSetting(FiniteWithin(depth_noise_coeff, 0.0, 0.1), "depth_noise_coeff",
                       depth_noise_coeff, "must be in [0, 0.1]");
  RequireSensorSetting(FiniteWithin(depth_factor, 1.0, 1e6), "depth_factor", depth_factor,
                       "must be in [1, 1e6]");
  RequireSensorSetting(FiniteWithin(edge_jump_ratio, 1e-4, 1.0), "edge_jump_ratio", edge_jump_ratio,
                       "must be in [0.0001, 1]");
  RequireSensorSetting(FiniteWithin(edge_hole_probability, 0.0, 1.0), "edge_hole_probability",
                       edge_hole_probability, "must be in [0, 1]");
  RequireSensorSetting(FiniteWithin(grazing_angle_deg, 1.0, 90.0), "grazing_angle_deg",
                       grazing_angle_deg, "must be in [1, 90]");
  RequireSensorSetting(FiniteWithin(min_range, 0.0, 100.0), "min_range", min_range,
                       "must be in [0, 100]");
  RequireSensorSetting(FiniteWithin(max_range, 0.0, 100.0) && max_range > min_range, "max_range",
                       max_range, "must be in (min_range, 100]");
  RequireSensorSetting(FiniteWithin(color_noise_sigma, 0.0, 50.0), "color_noise_sigma",
                       color_noise_sigma, "must be in [0, 50]");
  RequireSensorSetting(FiniteWithin(exposure_amplitude, 0.0, 0.5), "exposure_amplitude",
                       exposure_amplitude, "must be in [0, 0.5]");
  RequireSensorSetting(FiniteWithin(exposure_time, 1e-4, 0.2), "exposure_time", exposure_time,
                       "must be in [0.0001, 0.2]");
  RequireSensorSetting(blur_samples >= 2 && blur_samples <= 64, "blur_samples", blur_samples,
                       "must be in 2..64");
}

SensorModel::SensorModel(const SensorOptions& options, const CameraOptions& camera, uint32_t seed)
    : options_(options), camera_(camera), seed_(seed) {
  options_.Check();
  exposure_phase_[0] = 2.0 * M_PI * HashUniform(HashKey(seed, 101));
  exposure_phase_[1] = 2.0 * M_PI * HashUniform(HashKey(seed, 102));
}

double SensorModel::ExposureGain(double t) const {
  if (!options_.exposure) return 1.0;
  // Two incommensurate periods: a slow drift and a quicker wobble, as auto-exposure hunts.
  const double wave = 0.6 * std::sin(2.0 * M_PI * t / 7.3 + exposure_phase_[0]) +
                      0.4 * std::sin(2.0 * M_PI * t / 2.9 + exposure_phase_[1]);
  return 1.0 + options_.exposure_amplitude * wave;
}

void SensorModel::Apply(int frame, double t, const SE3& T_start_now, RenderBuffers* buffers) const {
  const cv::Mat clean_bgr = buffers->bgr;
  const cv::Mat clean_depth = buffers->depth;
  const cv::Mat& incidence = buffers->incidence;
  const int width = clean_bgr.cols, height = clean_bgr.rows;
  cv::Mat bgr(height, width, CV_8UC3);
  cv::Mat depth(height, width, CV_32FC1);
  const float gain = static_cast<float>(ExposureGain(t));
  const uint64_t frame_key = HashKey(seed_, static_cast<uint64_t>(frame) + 0x51ED);
  const float min_incidence =
      static_cast<float>(std::cos(options_.grazing_angle_deg * M_PI / 180.0));
  const Eigen::Matrix3d blur_R = T_start_now.Rotation();
  const Eigen::Vector3d blur_t = T_start_now.Translation();
  const SensorOptions& o = options_;
  const int rows_per_band = (height + kNoiseBands - 1) / kNoiseBands;

  cv::parallel_for_(
      cv::Range(0, kNoiseBands),
      [&](const cv::Range& range) {
        for (int band = range.start; band < range.end; ++band) {
          const int row0 = band * rows_per_band;
          const int row1 = std::min(height, row0 + rows_per_band);
          for (int y = row0; y < row1; ++y) {
            const float* z_row = clean_depth.ptr<float>(y);
            const float* incidence_row = incidence.ptr<float>(y);
            const uint8_t* in_row = clean_bgr.ptr<uint8_t>(y);
            uint8_t* out_row = bgr.ptr<uint8_t>(y);
            float* depth_row = depth.ptr<float>(y);
            for (int x = 0; x < width; ++x) {
              const uint64_t pixel_key =
                  MixBits(frame_key ^ (static_cast<uint64_t>(y) * width + x));
              const float z = z_row[x];

              float colour[3] = {static_cast<float>(in_row[3 * x]),
                                 static_cast<float>(in_row[3 * x + 1]),
                                 static_cast<float>(in_row[3 * x + 2])};
              if (o.motion_blur && z > 0.0f) {
                const Eigen::Vector3d now((x - camera_.cx) * z / camera_.fx,
                                          (y - camera_.cy) * z / camera_.fy, z);
                const Eigen::Vector3d start = blur_R * now + blur_t;
                if (start.z() > 1e-3) {
                  // The pixel saw, during the exposure, what now lies along p + s * (p - p_start).
                  const float flow_x =
                      static_cast<float>(x - (camera_.fx * start.x() / start.z() + camera_.cx));
                  const float flow_y =
                      static_cast<float>(y - (camera_.fy * start.y() / start.z() + camera_.cy));
                  float sum[3] = {0.0f, 0.0f, 0.0f};
                  for (int s = 0; s < o.blur_samples; ++s) {
                    const float step = static_cast<float>(s) / (o.blur_samples - 1);
                    float sample[3];
                    SampleColour(clean_bgr, x + step * flow_x, y + step * flow_y, sample);
                    for (int c = 0; c < 3; ++c) sum[c] += sample[c];
                  }
                  for (int c = 0; c < 3; ++c) colour[c] = sum[c] / o.blur_samples;
                }
              }
              for (int c = 0; c < 3; ++c) {
                float value = colour[c] * gain;
                if (o.color_noise) {
                  value += static_cast<float>(o.color_noise_sigma) *
                           HashGaussian(MixBits(pixel_key + 1 + static_cast<uint64_t>(c)));
                }
                out_row[3 * x + c] =
                    static_cast<uint8_t>(std::min(255.0f, std::max(0.0f, value + 0.5f)));
              }

              float d = z;
              if (d > 0.0f && o.range_limits && (d < o.min_range || d > o.max_range)) d = 0.0f;
              if (d > 0.0f && o.grazing_holes && incidence_row[x] < min_incidence) d = 0.0f;
              if (d > 0.0f && o.edge_holes) {
                float jump = 0.0f;
                if (x > 0) jump = std::max(jump, std::fabs(z - z_row[x - 1]));
                if (x + 1 < width) jump = std::max(jump, std::fabs(z - z_row[x + 1]));
                if (y > 0) jump = std::max(jump, std::fabs(z - clean_depth.ptr<float>(y - 1)[x]));
                if (y + 1 < height)
                  jump = std::max(jump, std::fabs(z - clean_depth.ptr<float>(y + 1)[x]));
                if (jump > o.edge_jump_ratio * z &&
                    HashUniform(MixBits(pixel_key + 7)) < o.edge_hole_probability) {
                  d = 0.0f;
                }
              }
              if (d > 0.0f && o.depth_noise) {
                d += static_cast<float>(o.depth_noise_coeff) * d * d *
                     HashGaussian(MixBits(pixel_key + 11));
                d = std::max(d, 1e-4f);
              }
              if (d > 0.0f && o.depth_quantization) {
                d = static_cast<float>(std::round(d * o.depth_factor) / o.depth_factor);
              }
              depth_row[x] = d;
            }
          }
        }
      },
      kNoiseBands);
  buffers->bgr = bgr;
  buffers->depth = depth;
}

}  // namespace drvslam::synth
