#include "drvslam/tools/synth/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <opencv2/core/utility.hpp>

#include "drvslam/core/error.h"

namespace drvslam::synth {
namespace {

// Row bands drawn in parallel. Fixed (not the thread count) so that work division, and hence
// every floating-point operation, is the same on any machine.
constexpr int kBands = 16;
// Barycentric slack for pixel centres exactly on an edge: shared edges are then covered by
// both triangles (the depth test picks one) instead of by neither.
constexpr double kEdgeSlack = 1e-9;

struct Vertex {
  Eigen::Vector3d p;  // camera frame
  Eigen::Vector2d uv;
};

// One triangle after clipping and projection, with everything the pixel loops need as planes
// over the image: value(x, y) = a * x + b * y + c.
struct ScreenTriangle {
  double bary[3][3];  // barycentric coordinate k
  double inv_z[3];
  double u_over_z[3];
  double v_over_z[3];
  int x0, x1, y0, y1;  // inclusive pixel bounds
  const Texture* texture;
  float texture_w, texture_h;
  float shade;
  float normal[3];  // unit, camera frame, facing the camera
  uint16_t instance;
  bool alpha_test;
};

// log2 to about 0.01, from the float's exponent and a quadratic in its mantissa: enough to
// pick mip levels, and several times cheaper than std::log2.
inline float FastLog2(float value) {
  if (!(value > 1e-30f)) return -100.0f;
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  const int exponent = static_cast<int>((bits >> 23) & 0xFF) - 127;
  const float mantissa = static_cast<float>(bits & 0x7FFFFF) * (1.0f / 8388608.0f);
  return static_cast<float>(exponent) + mantissa * (1.3465553f - 0.3465553f * mantissa);
}

inline double Plane(const double plane[3], double x, double y) {
  return plane[0] * x + plane[1] * y + plane[2];
}

// Clips a triangle against z >= near (Sutherland-Hodgman with one plane): 0, 3 or 4 corners.
int ClipNear(const Vertex in[3], double near, Vertex out[4]) {
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    const Vertex& a = in[i];
    const Vertex& b = in[(i + 1) % 3];
    const bool a_in = a.p.z() >= near;
    const bool b_in = b.p.z() >= near;
    if (a_in) out[count++] = a;
    if (a_in != b_in) {
      const double t = (near - a.p.z()) / (b.p.z() - a.p.z());
      Vertex v;
      v.p = a.p + t * (b.p - a.p);
      v.p.z() = near;
      v.uv = a.uv + t * (b.uv - a.uv);
      out[count++] = v;
    }
  }
  return count;
}

}  // namespace

void RasterOptions::Check() const {
  if (!(near_plane > 0.0) || !std::isfinite(near_plane)) {
    throw Error("raster near_plane must be a positive number");
  }
  if (!light_direction.allFinite() || light_direction.norm() < 1e-9) {
    throw Error("raster light_direction must be a non-zero vector");
  }
  if (!(ambient >= 0.0 && ambient <= 1.0)) throw Error("raster ambient must be in [0, 1]");
}

Rasterizer::Rasterizer(const CameraOptions& camera, const RasterOptions& options)
    : camera_(camera), options_(options) {
  camera_.Check();
  options_.Check();
  light_ = options_.light_direction.normalized();
}

void Rasterizer::Render(const std::vector<const TriangleList*>& lists,
                        const std::vector<Texture>& textures, const SE3& T_cw,
                        RenderBuffers* out) const {
  RenderRows(lists, textures, T_cw, 0, camera_.height, out);
}

void Rasterizer::RenderRows(const std::vector<const TriangleList*>& lists,
                            const std::vector<Texture>& textures, const SE3& T_cw, int row_begin,
                            int row_end, RenderBuffers* out, bool parallel) const {
  const int width = camera_.width;
  const int height = camera_.height;
  if (row_begin < 0 || row_end > height || row_begin >= row_end) {
    throw Error("rasterizer: rows " + std::to_string(row_begin) + ".." + std::to_string(row_end) +
                " are not a range inside 0.." + std::to_string(height));
  }
  const int rows = row_end - row_begin;
  const double fx = camera_.fx, fy = camera_.fy, cx = camera_.cx, cy = camera_.cy;
  const Eigen::Matrix3d R = T_cw.Rotation();
  const Eigen::Vector3d t = T_cw.Translation();

  std::vector<ScreenTriangle> screen;
  for (const TriangleList* list : lists) {
    for (const Triangle& triangle : *list) {
      if (triangle.texture < 0 || triangle.texture >= static_cast<int>(textures.size())) {
        throw Error("rasterizer: triangle names texture " + std::to_string(triangle.texture) +
                    " of " + std::to_string(textures.size()));
      }
      Vertex corners[3];
      for (int k = 0; k < 3; ++k) {
        corners[k].p = R * triangle.p[k] + t;
        corners[k].uv = triangle.uv[k].cast<double>();
      }
      Eigen::Vector3d normal = (corners[1].p - corners[0].p).cross(corners[2].p - corners[0].p);
      const double normal_length = normal.norm();
      if (!(normal_length > 0.0)) continue;
      normal /= normal_length;
      if (normal.dot(corners[0].p) >= 0.0) {
        if (!triangle.double_sided) continue;  // back face
        normal = -normal;
      }
      const Eigen::Vector3d normal_world = R.transpose() * normal;
      const float shade = static_cast<float>(
          options_.ambient + (1.0 - options_.ambient) * std::max(0.0, normal_world.dot(light_)));

      Vertex clipped[4];
      const int count = ClipNear(corners, options_.near_plane, clipped);
      for (int fan = 1; fan + 1 < count; ++fan) {
        const Vertex* v[3] = {&clipped[0], &clipped[fan], &clipped[fan + 1]};
        double sx[3], sy[3], iz[3];
        for (int k = 0; k < 3; ++k) {
          iz[k] = 1.0 / v[k]->p.z();
          sx[k] = fx * v[k]->p.x() * iz[k] + cx;
          sy[k] = fy * v[k]->p.y() * iz[k] + cy;
        }
        const double area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
        if (!(std::fabs(area) > 1e-12)) continue;
        ScreenTriangle s;
        s.x0 = std::max(0, static_cast<int>(std::ceil(std::min({sx[0], sx[1], sx[2]}) - 1e-6)));
        s.x1 = std::min(
            width - 1,
            static_cast<int>(std::floor(std::min(std::max({sx[0], sx[1], sx[2]}) + 1e-6, 1e9))));
        s.y0 = std::max(row_begin,
                        static_cast<int>(std::ceil(std::min({sy[0], sy[1], sy[2]}) - 1e-6)));
        s.y1 = std::min(
            row_end - 1,
            static_cast<int>(std::floor(std::min(std::max({sy[0], sy[1], sy[2]}) + 1e-6, 1e9))));
        if (s.x0 > s.x1 || s.y0 > s.y1) continue;
        for (int k = 0; k < 3; ++k) {
          const int i = (k + 1) % 3, j = (k + 2) % 3;
          s.bary[k][0] = (sy[i] - sy[j]) / area;
          s.bary[k][1] = (sx[j] - sx[i]) / area;
          s.bary[k][2] = (sx[i] * sy[j] - sx[j] * sy[i]) / area;
        }
        for (int c = 0; c < 3; ++c) {
          s.inv_z[c] = s.u_over_z[c] = s.v_over_z[c] = 0.0;
          for (int k = 0; k < 3; ++k) {
            s.inv_z[c] += s.bary[k][c] * iz[k];
            s.u_over_z[c] += s.bary[k][c] * v[k]->uv.x() * iz[k];
            s.v_over_z[c] += s.bary[k][c] * v[k]->uv.y() * iz[k];
          }
        }
        s.texture = &textures[triangle.texture];
        s.texture_w = static_cast<float>(s.texture->Width());
        s.texture_h = static_cast<float>(s.texture->Height());
        s.shade = shade;
        for (int k = 0; k < 3; ++k) s.normal[k] = static_cast<float>(normal[k]);
        s.instance = static_cast<uint16_t>(std::clamp(triangle.instance_id, 0, 65535));
        s.alpha_test = s.texture->HasTransparency();
        screen.push_back(s);
      }
    }
  }

  out->bgr.create(rows, width, CV_8UC3);
  out->depth.create(rows, width, CV_32FC1);
  out->instance.create(rows, width, CV_16UC1);
  out->incidence.create(rows, width, CV_32FC1);
  // Indexed by image row minus row_begin.
  std::vector<double> nearest(static_cast<std::size_t>(width) * rows);
  std::vector<int> owner(static_cast<std::size_t>(width) * rows);
  const int rows_per_band = (rows + kBands - 1) / kBands;

  const auto draw_bands = [&](const cv::Range& range) {
    for (int band = range.start; band < range.end; ++band) {
      const int row0 = row_begin + band * rows_per_band;
      const int row1 = std::min(row_end, row0 + rows_per_band);
      if (row0 >= row1) continue;
      std::fill(nearest.begin() + static_cast<std::ptrdiff_t>(row0 - row_begin) * width,
                nearest.begin() + static_cast<std::ptrdiff_t>(row1 - row_begin) * width, 0.0);
      std::fill(owner.begin() + static_cast<std::ptrdiff_t>(row0 - row_begin) * width,
                owner.begin() + static_cast<std::ptrdiff_t>(row1 - row_begin) * width, -1);

      // Visibility: the largest 1/z (nearest surface) at each pixel centre.
      for (int index = 0; index < static_cast<int>(screen.size()); ++index) {
        const ScreenTriangle& s = screen[index];
        const int y_begin = std::max(s.y0, row0);
        const int y_end = std::min(s.y1, row1 - 1);
        for (int y = y_begin; y <= y_end; ++y) {
          // Span of x where all three barycentric coordinates are >= -slack on this row.
          double lo = s.x0, hi = s.x1;
          bool empty = false;
          for (int k = 0; k < 3 && !empty; ++k) {
            const double a = s.bary[k][0];
            const double rest = s.bary[k][1] * y + s.bary[k][2] + kEdgeSlack;
            if (a > 0.0) {
              lo = std::max(lo, -rest / a);
            } else if (a < 0.0) {
              hi = std::min(hi, -rest / a);
            } else if (rest < 0.0) {
              empty = true;
            }
          }
          if (empty || !(lo <= hi)) continue;
          const int x_begin = static_cast<int>(std::ceil(lo));
          const int x_end = static_cast<int>(std::floor(hi));
          double* depth_row = nearest.data() + static_cast<std::ptrdiff_t>(y - row_begin) * width;
          int* owner_row = owner.data() + static_cast<std::ptrdiff_t>(y - row_begin) * width;
          for (int x = x_begin; x <= x_end; ++x) {
            const double q = Plane(s.inv_z, x, y);
            if (!(q > depth_row[x])) continue;
            if (s.alpha_test) {
              const float u = static_cast<float>(Plane(s.u_over_z, x, y) / q);
              const float v = static_cast<float>(Plane(s.v_over_z, x, y) / q);
              if (!s.texture->Opaque(u, v)) continue;
            }
            depth_row[x] = q;
            owner_row[x] = index;
          }
        }
      }

      // Shading of the visible surface only.
      for (int y = row0; y < row1; ++y) {
        const double* depth_row =
            nearest.data() + static_cast<std::ptrdiff_t>(y - row_begin) * width;
        const int* owner_row = owner.data() + static_cast<std::ptrdiff_t>(y - row_begin) * width;
        uint8_t* bgr_row = out->bgr.ptr<uint8_t>(y - row_begin);
        float* z_row = out->depth.ptr<float>(y - row_begin);
        uint16_t* id_row = out->instance.ptr<uint16_t>(y - row_begin);
        float* incidence_row = out->incidence.ptr<float>(y - row_begin);
        const float ray_y = static_cast<float>((y - cy) / fy);
        for (int x = 0; x < width; ++x) {
          const int index = owner_row[x];
          if (index < 0) {
            bgr_row[3 * x] = bgr_row[3 * x + 1] = bgr_row[3 * x + 2] = 0;
            z_row[x] = 0.0f;
            id_row[x] = 0;
            incidence_row[x] = 0.0f;
            continue;
          }
          const ScreenTriangle& s = screen[index];
          const double q = depth_row[x];
          const double inv_q = 1.0 / q;
          const double u = Plane(s.u_over_z, x, y) * inv_q;
          const double v = Plane(s.v_over_z, x, y) * inv_q;
          // Texture footprint of one pixel, from the derivatives of u = (u/z) / (1/z).
          const double du_dx = (s.u_over_z[0] - u * s.inv_z[0]) * inv_q * s.texture_w;
          const double du_dy = (s.u_over_z[1] - u * s.inv_z[1]) * inv_q * s.texture_w;
          const double dv_dx = (s.v_over_z[0] - v * s.inv_z[0]) * inv_q * s.texture_h;
          const double dv_dy = (s.v_over_z[1] - v * s.inv_z[1]) * inv_q * s.texture_h;
          const double footprint =
              std::max(du_dx * du_dx + dv_dx * dv_dx, du_dy * du_dy + dv_dy * dv_dy);
          const float lod = 0.5f * FastLog2(static_cast<float>(footprint));
          float colour[3];
          s.texture->Sample(static_cast<float>(u), static_cast<float>(v), lod, colour);
          for (int c = 0; c < 3; ++c) {
            const float value = colour[c] * s.shade + 0.5f;
            bgr_row[3 * x + c] = static_cast<uint8_t>(std::min(255.0f, std::max(0.0f, value)));
          }
          z_row[x] = static_cast<float>(inv_q);
          id_row[x] = s.instance;
          const float ray_x = static_cast<float>((x - cx) / fx);
          const float dot = s.normal[0] * ray_x + s.normal[1] * ray_y + s.normal[2];
          incidence_row[x] = std::fabs(dot) / std::sqrt(ray_x * ray_x + ray_y * ray_y + 1.0f);
        }
      }
    }
  };
  if (parallel) {
    cv::parallel_for_(cv::Range(0, kBands), draw_bands, kBands);
  } else {
    draw_bands(cv::Range(0, kBands));
  }
}

}  // namespace drvslam::synth
