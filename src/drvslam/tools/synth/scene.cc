#include "drvslam/tools/synth/scene.h"

#include <cmath>

namespace drvslam::synth {

void AddQuad(const Eigen::Vector3d& bottom_left, const Eigen::Vector3d& bottom_right,
             const Eigen::Vector3d& top_right, const Eigen::Vector3d& top_left, const UvRect& uv,
             const SurfaceTag& tag, TriangleList* out) {
  const Eigen::Vector2f uv_bl(uv.u0, uv.v1), uv_br(uv.u1, uv.v1), uv_tr(uv.u1, uv.v0),
      uv_tl(uv.u0, uv.v0);
  Triangle first;
  first.p = {bottom_left, bottom_right, top_right};
  first.uv = {uv_bl, uv_br, uv_tr};
  first.texture = tag.texture;
  first.instance_id = tag.instance_id;
  first.double_sided = tag.double_sided;
  Triangle second = first;
  second.p = {bottom_left, top_right, top_left};
  second.uv = {uv_bl, uv_tr, uv_tl};
  out->push_back(first);
  out->push_back(second);
}

Eigen::Vector2d BoxAtlasSize(const Eigen::Vector3d& size) {
  return {2.0 * (size.x() + size.y()), size.z() + size.y()};
}

UvRect BoxAtlasFace(const Eigen::Vector3d& size, int face_index) {
  const Eigen::Vector2d atlas = BoxAtlasSize(size);
  const double w = atlas.x(), h = atlas.y();
  // Left edge and width of each face's column, and whether it sits in the upper (sides) row.
  const double sx = size.x(), sy = size.y(), sz = size.z();
  double left = 0.0, width = sx;
  bool upper = true;
  switch (face_index) {
    case 0:
      left = 0.0, width = sx;
      break;
    case 1:
      left = sx, width = sy;
      break;
    case 2:
      left = sx + sy, width = sx;
      break;
    case 3:
      left = 2.0 * sx + sy, width = sy;
      break;
    case 4:
      left = 0.0, width = sx, upper = false;
      break;
    default:
      left = sx, width = sx, upper = false;
      break;
  }
  UvRect rect;
  rect.u0 = static_cast<float>(left / w);
  rect.u1 = static_cast<float>((left + width) / w);
  rect.v0 = static_cast<float>(upper ? 0.0 : sz / h);
  rect.v1 = static_cast<float>(upper ? sz / h : 1.0);
  return rect;
}

void AddBox(const SE3& pose, const Eigen::Vector3d& size, const SurfaceTag& tag,
            TriangleList* out) {
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y(), hz = 0.5 * size.z();
  const auto corner = [&](double x, double y, double z) { return pose * Eigen::Vector3d(x, y, z); };
  // Each face: bottom-left, bottom-right, top-right, top-left as seen from outside.
  AddQuad(corner(-hx, -hy, -hz), corner(hx, -hy, -hz), corner(hx, -hy, hz), corner(-hx, -hy, hz),
          BoxAtlasFace(size, 0), tag, out);
  AddQuad(corner(hx, -hy, -hz), corner(hx, hy, -hz), corner(hx, hy, hz), corner(hx, -hy, hz),
          BoxAtlasFace(size, 1), tag, out);
  AddQuad(corner(hx, hy, -hz), corner(-hx, hy, -hz), corner(-hx, hy, hz), corner(hx, hy, hz),
          BoxAtlasFace(size, 2), tag, out);
  AddQuad(corner(-hx, hy, -hz), corner(-hx, -hy, -hz), corner(-hx, -hy, hz), corner(-hx, hy, hz),
          BoxAtlasFace(size, 3), tag, out);
  AddQuad(corner(-hx, -hy, hz), corner(hx, -hy, hz), corner(hx, hy, hz), corner(-hx, hy, hz),
          BoxAtlasFace(size, 4), tag, out);
  AddQuad(corner(-hx, hy, -hz), corner(hx, hy, -hz), corner(hx, -hy, -hz), corner(-hx, -hy, -hz),
          BoxAtlasFace(size, 5), tag, out);
}

Eigen::Vector2d CylinderAtlasSize(double radius, double height) {
  return {2.0 * M_PI * radius, height + 2.0 * radius};
}

void AddCylinder(const SE3& pose, double radius, double height, int segments, const SurfaceTag& tag,
                 TriangleList* out) {
  const Eigen::Vector2d atlas = CylinderAtlasSize(radius, height);
  const float side_v1 = static_cast<float>(height / atlas.y());
  const float cap_u = static_cast<float>(2.0 * radius / atlas.x());
  const auto rim = [&](int k, double z) {
    const double angle = 2.0 * M_PI * k / segments;
    return pose * Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), z);
  };
  for (int k = 0; k < segments; ++k) {
    UvRect uv;
    uv.u0 = static_cast<float>(k) / segments;
    uv.u1 = static_cast<float>(k + 1) / segments;
    uv.v0 = 0.0f;
    uv.v1 = side_v1;
    AddQuad(rim(k, 0.0), rim(k + 1, 0.0), rim(k + 1, height), rim(k, height), uv, tag, out);
  }
  // Top cap as a fan; its texture is the disc inscribed in the square below the side strip.
  const auto cap_uv = [&](int k) {
    const double angle = 2.0 * M_PI * k / segments;
    return Eigen::Vector2f(
        static_cast<float>(0.5 * cap_u * (1.0 + std::cos(angle))),
        side_v1 + static_cast<float>(0.5 * (1.0 - side_v1) * (1.0 - std::sin(angle))));
  };
  for (int k = 1; k + 1 < segments; ++k) {
    Triangle t;
    t.p = {rim(0, height), rim(k, height), rim(k + 1, height)};
    t.uv = {cap_uv(0), cap_uv(k), cap_uv(k + 1)};
    t.texture = tag.texture;
    t.instance_id = tag.instance_id;
    t.double_sided = tag.double_sided;
    out->push_back(t);
  }
}

void TransformTriangles(const SE3& transform, TriangleList* triangles) {
  for (Triangle& t : *triangles) {
    for (Eigen::Vector3d& p : t.p) p = transform * p;
  }
}

}  // namespace drvslam::synth
