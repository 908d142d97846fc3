#include "drvslam/dense/dense_surface.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr float kMinWeightDepth = 0.1f;
// Without DenseMap.flyingPixelStep, a 3 % step still separates surfaces (its default).
constexpr float kDefaultSurfaceStep = 0.03f;

bool Near(float a, float b, float step) { return std::abs(a - b) <= step * b; }

// One 1-D pass: sums (and counts) of `values` (`counts`) over the usable pixels within
// `radius` along a row or a column whose depth lies on the centre's surface. The first pass sums
// depths and ones, the second the first pass's sums.
void SumAlong(const cv::Mat& depth, const cv::Mat& usable, const cv::Mat& values,
              const cv::Mat& counts, int radius, float step, bool vertical, cv::Mat* sums,
              cv::Mat* totals) {
  const int w = depth.cols, h = depth.rows;
  for (int y = 0; y < h; ++y) {
    const float* d = depth.ptr<float>(y);
    const uint8_t* u = usable.ptr<uint8_t>(y);
    float* s = sums->ptr<float>(y);
    float* t = totals->ptr<float>(y);
    std::fill(s, s + w, 0.0f);
    std::fill(t, t + w, 0.0f);
    if (vertical) {
      // Row by row over the window, so memory is read in order.
      for (int qy = std::max(0, y - radius); qy <= std::min(h - 1, y + radius); ++qy) {
        const float* qd = depth.ptr<float>(qy);
        const uint8_t* qu = usable.ptr<uint8_t>(qy);
        const float* qv = values.ptr<float>(qy);
        const float* qc = counts.ptr<float>(qy);
        for (int x = 0; x < w; ++x) {
          if (u[x] && qu[x] && Near(qd[x], d[x], step)) {
            s[x] += qv[x];
            t[x] += qc[x];
          }
        }
      }
      continue;
    }
    const float* v = values.ptr<float>(y);
    const float* c = counts.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (!u[x]) continue;
      for (int qx = std::max(0, x - radius); qx <= std::min(w - 1, x + radius); ++qx) {
        if (u[qx] && Near(d[qx], d[x], step)) {
          s[x] += v[qx];
          t[x] += c[qx];
        }
      }
    }
  }
}

// The surface point of pixel (x, y): its ray scaled by its depth.
Eigen::Vector3f PointAt(const cv::Mat& depth, const PixelRays& rays, int x, int y) {
  const cv::Vec2f& r = rays.xy.ptr<cv::Vec2f>(y)[x];
  const float z = depth.ptr<float>(y)[x];
  return {r[0] * z, r[1] * z, z};
}

// A tangent of the surface at (x, y) along (dx, dy): between the neighbours `radius` pixels on
// either side, or one side and the centre where the other is off the surface.
bool Tangent(const cv::Mat& depth, const cv::Mat& usable, const PixelRays& rays, int x, int y,
             int dx, int dy, int radius, float step, Eigen::Vector3f* tangent) {
  const float z = depth.ptr<float>(y)[x];
  const auto on_surface = [&](int qx, int qy) {
    return qx >= 0 && qy >= 0 && qx < depth.cols && qy < depth.rows &&
           usable.ptr<uint8_t>(qy)[qx] && Near(depth.ptr<float>(qy)[qx], z, step * radius);
  };
  const int ax = x + dx * radius, ay = y + dy * radius;
  const int bx = x - dx * radius, by = y - dy * radius;
  const bool ahead = on_surface(ax, ay), behind = on_surface(bx, by);
  if (!ahead && !behind) return false;
  const Eigen::Vector3f a = ahead ? PointAt(depth, rays, ax, ay) : PointAt(depth, rays, x, y);
  const Eigen::Vector3f b = behind ? PointAt(depth, rays, bx, by) : PointAt(depth, rays, x, y);
  *tangent = a - b;
  return true;
}

}  // namespace

float DepthNoiseWeight(float z) {
  const float clamped = std::max(z, kMinWeightDepth);
  const float z2 = clamped * clamped;
  return 1.0f / (z2 * z2);
}

cv::Mat SmoothDepthAlongSurfaces(const cv::Mat& depth, const cv::Mat& usable, int radius,
                                 float step) {
  cv::Mat smoothed = depth.clone();
  if (radius <= 0) return smoothed;
  const cv::Size size = depth.size();
  cv::Mat ones(size, CV_32FC1, cv::Scalar(1.0f));
  cv::Mat row_sums(size, CV_32FC1), row_counts(size, CV_32FC1);
  SumAlong(depth, usable, depth, ones, radius, step, /*vertical=*/false, &row_sums, &row_counts);
  cv::Mat sums(size, CV_32FC1), counts(size, CV_32FC1);
  SumAlong(depth, usable, row_sums, row_counts, radius, step, /*vertical=*/true, &sums, &counts);
  for (int y = 0; y < size.height; ++y) {
    const float* s = sums.ptr<float>(y);
    const float* c = counts.ptr<float>(y);
    float* out = smoothed.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      if (c[x] > 0.0f) out[x] = s[x] / c[x];
    }
  }
  return smoothed;
}

cv::Mat ViewCosines(const cv::Mat& depth, const cv::Mat& usable, const PixelRays& rays, int radius,
                    float step) {
  cv::Mat cosines = cv::Mat::zeros(depth.size(), CV_32FC1);
  const int r = std::max(radius, 1);
  for (int y = 0; y < depth.rows; ++y) {
    const uint8_t* u = usable.ptr<uint8_t>(y);
    const cv::Vec2f* ray = rays.xy.ptr<cv::Vec2f>(y);
    float* out = cosines.ptr<float>(y);
    for (int x = 0; x < depth.cols; ++x) {
      if (!u[x]) continue;
      Eigen::Vector3f along_x, along_y;
      float cosine = kMinViewCosine;
      if (Tangent(depth, usable, rays, x, y, 1, 0, r, step, &along_x) &&
          Tangent(depth, usable, rays, x, y, 0, 1, r, step, &along_y)) {
        const Eigen::Vector3f normal = along_x.cross(along_y);
        const Eigen::Vector3f view(ray[x][0], ray[x][1], 1.0f);
        const float norms = normal.norm() * view.norm();
        if (norms > 0.0f) cosine = std::max(std::abs(normal.dot(view)) / norms, kMinViewCosine);
      }
      out[x] = cosine;
    }
  }
  return cosines;
}

SurfaceSamples BackProjectSurfaces(const DenseFrame& frame, const PixelRoles& roles,
                                   const PixelRays& rays, const DenseMapOptions& options) {
  if (rays.xy.size() != frame.depth.size() || rays.xy.type() != CV_32FC2) {
    throw Error("dense frame " + std::to_string(frame.frame_id) +
                ": the camera's image size differs from the depth image's");
  }
  const float min_depth = static_cast<float>(options.min_depth);
  const float max_depth = static_cast<float>(options.max_depth);
  const uint8_t background = static_cast<uint8_t>(PixelRole::kBackground);
  cv::Mat usable(frame.depth.size(), CV_8UC1);
  for (int y = 0; y < frame.depth.rows; ++y) {
    const float* d = frame.depth.ptr<float>(y);
    const uint8_t* role = roles.role.ptr<uint8_t>(y);
    uint8_t* u = usable.ptr<uint8_t>(y);
    for (int x = 0; x < frame.depth.cols; ++x) {
      u[x] = role[x] == background && std::isfinite(d[x]) && d[x] > 0.0f && d[x] >= min_depth &&
             d[x] <= max_depth;
    }
  }
  const float step = options.flying_pixel_step > 0.0 ? static_cast<float>(options.flying_pixel_step)
                                                     : kDefaultSurfaceStep;
  const cv::Mat depth =
      SmoothDepthAlongSurfaces(frame.depth, usable, options.depth_smoothing, step);
  const cv::Mat cosines = ViewCosines(depth, usable, rays, options.depth_smoothing, step);
  SurfaceSamples samples;
  for (int y = 0; y < depth.rows; ++y) {
    const cv::Vec2f* ray = rays.xy.ptr<cv::Vec2f>(y);
    const float* d = depth.ptr<float>(y);
    const float* cosine = cosines.ptr<float>(y);
    const uint8_t* u = usable.ptr<uint8_t>(y);
    const int16_t* labels = roles.label.ptr<int16_t>(y);
    const int32_t* tracks = roles.track.ptr<int32_t>(y);
    const cv::Vec3b* colour = frame.bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < depth.cols; ++x) {
      if (!u[x]) continue;
      const float z = d[x];
      samples.points.push_back(PixelPoint(ray[x], z, colour[x], labels[x], tracks[x]));
      samples.weights.push_back(cosine[x] * DepthNoiseWeight(z));
    }
  }
  return samples;
}

}  // namespace drvslam
