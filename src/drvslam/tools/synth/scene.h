// Scene geometry: textured triangles tagged with an instance id, and helpers that build quads,
// boxes and cylinders with their texture coordinates. The room, the furniture, the key objects
// and the actors are all made of these; the rasterizer draws nothing else.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "drvslam/core/se3.h"

namespace drvslam::synth {

struct Triangle {
  // Corners counter-clockwise seen from the front side (outside of a solid).
  std::array<Eigen::Vector3d, 3> p;
  std::array<Eigen::Vector2f, 3> uv;  // normalized texture coordinates
  int texture = 0;
  int instance_id = 0;  // 0 = background (room, furniture)
  // Seen from both sides (billboards); otherwise back faces are culled.
  bool double_sided = false;
};

using TriangleList = std::vector<Triangle>;

// Texture coordinates of a rectangle: (u0, v0) top-left, (u1, v1) bottom-right.
struct UvRect {
  float u0 = 0.0f, v0 = 0.0f, u1 = 1.0f, v1 = 1.0f;
};

// What every triangle of one added solid shares.
struct SurfaceTag {
  int texture = 0;
  int instance_id = 0;
  bool double_sided = false;
};

// A planar quad from its corners as seen from the front: bottom-left, bottom-right, top-right,
// top-left. The texture's top-left corner lands on top_left.
void AddQuad(const Eigen::Vector3d& bottom_left, const Eigen::Vector3d& bottom_right,
             const Eigen::Vector3d& top_right, const Eigen::Vector3d& top_left, const UvRect& uv,
             const SurfaceTag& tag, TriangleList* out);

// Physical size (width, height in metres) of a box's texture atlas: its four sides side by side
// (-y, +x, +y, -x faces, height size.z), then top and bottom below them (height size.y).
// Painting a texture of this size keeps texel density equal on all faces.
Eigen::Vector2d BoxAtlasSize(const Eigen::Vector3d& size);
// Where one face sits in a box's atlas (normalized), in atlas order: 0 = -y, 1 = +x, 2 = +y,
// 3 = -x, 4 = top, 5 = bottom; e.g. to paint a face on the front of a head.
UvRect BoxAtlasFace(const Eigen::Vector3d& size, int face_index);

// A box with the given size, centred at pose.Translation(), axes along pose's rotation.
void AddBox(const SE3& pose, const Eigen::Vector3d& size, const SurfaceTag& tag, TriangleList* out);

// Physical size of a cylinder's atlas: the side unrolled (2 pi r by height), then the top cap
// (2r by 2r) below it.
Eigen::Vector2d CylinderAtlasSize(double radius, double height);
// A closed cylinder (side and top cap; the bottom is never seen on a table) standing on
// pose.Translation(), axis along pose's z, approximated by `segments` flat sides.
void AddCylinder(const SE3& pose, double radius, double height, int segments, const SurfaceTag& tag,
                 TriangleList* out);

// Applies a rigid transform to every corner.
void TransformTriangles(const SE3& transform, TriangleList* triangles);

}  // namespace drvslam::synth
