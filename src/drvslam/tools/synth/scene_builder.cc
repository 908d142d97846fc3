#include "drvslam/tools/synth/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "drvslam/core/coco_classes.h"
#include "drvslam/tools/synth/random.h"

namespace drvslam::synth {
namespace {

// Texel densities (texels per metre): one texel is about one pixel at 1.7 m for the walls, and
// finer on furniture and objects that the camera sees from closer.
constexpr double kWallDensity = 320.0;
constexpr double kFloorDensity = 280.0;
constexpr double kCeilingDensity = 200.0;
constexpr double kFurnitureDensity = 380.0;
constexpr double kObjectDensity = 500.0;
// Walls, floor and ceiling are cut into panels no longer than this, each with its own texture,
// so that a big room keeps its texel density.
constexpr double kMaxPanel = 3.0;

SE3 Pose(double x, double y, double z, double yaw = 0.0) {
  return SE3(Eigen::Matrix3d(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())),
             Eigen::Vector3d(x, y, z));
}

class Builder {
 public:
  Builder(const RoomLayout& layout, uint64_t seed, TextureBank* bank)
      : layout_(layout), seed_(seed), rng_(SubSeed(seed, RandomStream::kLayout)), bank_(bank) {}

  StaticScene Build() {
    AddRoom();
    AddTable();
    AddStools();
    AddShelves();
    AddFloorClutter();
    AddKeyObjects();
    return std::move(scene_);
  }

 private:
  cv::Vec3b RandomColour(double min_value, double max_value) {
    // A saturated colour from a random hue, for labels, covers and cases.
    const double hue = rng_.Uniform(0.0, 6.0);
    const double value = rng_.Uniform(min_value, max_value);
    const double saturation = rng_.Uniform(0.4, 1.0);
    double rgb[3] = {0, 0, 0};
    const double chroma = value * saturation;
    const double x = chroma * (1.0 - std::fabs(std::fmod(hue, 2.0) - 1.0));
    const int sector = static_cast<int>(hue);
    const int order[6][2] = {{0, 1}, {1, 0}, {1, 2}, {2, 1}, {2, 0}, {0, 2}};
    rgb[order[sector][0]] = chroma;
    rgb[order[sector][1]] = x;
    const double m = value - chroma;
    return cv::Vec3b(static_cast<uint8_t>(255 * (rgb[2] + m)),
                     static_cast<uint8_t>(255 * (rgb[1] + m)),
                     static_cast<uint8_t>(255 * (rgb[0] + m)));
  }

  int Texture(double width_m, double height_m, double density, TextureStyle style,
              cv::Vec3b colour = {128, 128, 128}, double saturation = 1.0,
              double brightness = 1.0) {
    TextureRequest request;
    request.saturation = saturation;
    request.brightness = brightness;
    request.width_m = width_m;
    request.height_m = height_m;
    request.texels_per_metre = density;
    request.style = style;
    request.colour = colour;
    request.seed = SubSeed(seed_, RandomStream::kTextures, static_cast<uint64_t>(bank_->Size()));
    return bank_->Add(request);
  }

  // A new texture for a solid whose faces unfold into `atlas` (metres), on an instance.
  SurfaceTag SolidTag(const Eigen::Vector2d& atlas, double density, TextureStyle style,
                      int instance_id, cv::Vec3b colour) {
    SurfaceTag tag;
    tag.texture = Texture(atlas.x(), atlas.y(), density, style, colour);
    tag.instance_id = instance_id;
    return tag;
  }

  void Box(const SE3& pose, const Eigen::Vector3d& size, double density, TextureStyle style,
           int instance_id = 0, cv::Vec3b colour = {128, 128, 128}) {
    AddBox(pose, size, SolidTag(BoxAtlasSize(size), density, style, instance_id, colour),
           &scene_.triangles);
  }

  // An upright 16-sided object with a label texture; returns its tag for parts that share it.
  SurfaceTag LabelledCylinder(const SE3& base, double radius, double height, int instance_id,
                              cv::Vec3b colour) {
    const SurfaceTag tag = SolidTag(CylinderAtlasSize(radius, height), kObjectDensity,
                                    TextureStyle::kLabel, instance_id, colour);
    AddCylinder(base, radius, height, 16, tag, &scene_.triangles);
    return tag;
  }

  // A rectangle seen from the front, from its bottom-left corner along `right` and `up` (unit),
  // cut into panels of at most kMaxPanel.
  void Panels(const Eigen::Vector3d& bottom_left, const Eigen::Vector3d& right,
              const Eigen::Vector3d& up, double width, double height, double density,
              TextureStyle style, double saturation = 1.0, double brightness = 1.0) {
    const int columns = std::max(1, static_cast<int>(std::ceil(width / kMaxPanel)));
    const int rows = std::max(1, static_cast<int>(std::ceil(height / kMaxPanel)));
    const double w = width / columns, h = height / rows;
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < columns; ++c) {
        const Eigen::Vector3d bl = bottom_left + right * (c * w) + up * (r * h);
        SurfaceTag tag;
        tag.texture = Texture(w, h, density, style, {128, 128, 128}, saturation, brightness);
        AddQuad(bl, bl + right * w, bl + right * w + up * h, bl + up * h, UvRect(), tag,
                &scene_.triangles);
      }
    }
  }

  void AddRoom() {
    const Eigen::Vector3d& lo = layout_.min;
    const Eigen::Vector3d& hi = layout_.max;
    const double w = hi.x() - lo.x(), d = hi.y() - lo.y(), h = hi.z() - lo.z();
    const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                          ez = Eigen::Vector3d::UnitZ();
    // A darker, muted floor (a patterned carpet), a plaster ceiling, and walls full of posters.
    const TextureStyle wall = TextureStyle::kCollage;
    Panels({lo.x(), lo.y(), lo.z()}, ex, ey, w, d, kFloorDensity, TextureStyle::kProcedural, 0.6,
           0.85);
    Panels({lo.x(), hi.y(), hi.z()}, ex, -ey, w, d, kCeilingDensity, TextureStyle::kPlaster);
    Panels({lo.x(), hi.y(), lo.z()}, ex, ez, w, h, kWallDensity, wall);   // back
    Panels({hi.x(), lo.y(), lo.z()}, -ex, ez, w, h, kWallDensity, wall);  // front
    Panels({lo.x(), lo.y(), lo.z()}, ey, ez, d, h, kWallDensity, wall);   // left
    Panels({hi.x(), hi.y(), lo.z()}, -ey, ez, d, h, kWallDensity, wall);  // right
  }

  void AddTable() {
    const Eigen::Vector2d& size = layout_.table_size;
    const double top = layout_.table_height;
    Box(Pose(0, 0, top - 0.02), {size.x(), size.y(), 0.04}, kFurnitureDensity, TextureStyle::kDesk);
    const double leg_h = top - 0.04;
    for (const double sx : {-1.0, 1.0}) {
      for (const double sy : {-1.0, 1.0}) {
        Box(Pose(sx * (0.5 * size.x() - 0.06), sy * (0.5 * size.y() - 0.06), 0.5 * leg_h),
            {0.05, 0.05, leg_h}, kFurnitureDensity, TextureStyle::kWood);
      }
    }
  }

  void AddStools() {
    const int chair = CocoClassId("chair");
    for (const Eigen::Vector2d& seat : layout_.stools) {
      const int id = NextInstance("chair", chair);
      const double h = layout_.stool_height;
      const double yaw = rng_.Uniform(-0.3, 0.3);
      const SE3 base = Pose(seat.x(), seat.y(), 0.0, yaw);
      const cv::Vec3b colour = RandomColour(0.3, 0.9);
      Box(base * Pose(0, 0, h - 0.02), {0.38, 0.38, 0.04}, kFurnitureDensity, TextureStyle::kLabel,
          id, colour);
      for (const double sx : {-1.0, 1.0}) {
        for (const double sy : {-1.0, 1.0}) {
          Box(base * Pose(sx * 0.15, sy * 0.15, 0.5 * (h - 0.04)), {0.035, 0.035, h - 0.04},
              kFurnitureDensity, TextureStyle::kWood, id);
        }
      }
    }
  }

  // A shelf unit standing on the floor at `base` (its local x along the wall, y out of the
  // wall into the room), filled with boxes, binders and books.
  void ShelfUnit(const SE3& base, double width, double height, int boards) {
    const double depth = layout_.shelf_depth;
    const double board = 0.025;
    Box(base * Pose(-0.5 * width + 0.01, 0.5 * depth, 0.5 * height), {0.02, depth, height},
        kFurnitureDensity, TextureStyle::kWood);
    Box(base * Pose(0.5 * width - 0.01, 0.5 * depth, 0.5 * height), {0.02, depth, height},
        kFurnitureDensity, TextureStyle::kWood);
    Box(base * Pose(0, 0.006, 0.5 * height), {width - 0.04, 0.012, height}, kFurnitureDensity,
        TextureStyle::kPlaster);
    const double gap = (height - board) / boards;
    for (int k = 0; k <= boards; ++k) {
      const double z = k * gap + 0.5 * board;
      Box(base * Pose(0, 0.5 * depth + 0.006, z), {width - 0.04, depth - 0.012, board},
          kFurnitureDensity, TextureStyle::kWood);
      if (k == boards) break;
      // Items along the board, left to right, with random gaps.
      double x = -0.5 * width + 0.03 + rng_.Uniform(0.0, 0.05);
      while (true) {
        const bool upright_books = rng_.Chance(0.3);
        const double item_w = upright_books ? rng_.Uniform(0.02, 0.05) : rng_.Uniform(0.08, 0.3);
        if (x + item_w > 0.5 * width - 0.03) break;
        const double max_h = std::min(0.32, gap - board - 0.03);
        const double item_h =
            upright_books ? rng_.Uniform(0.6, 0.95) * max_h : rng_.Uniform(0.35, 1.0) * max_h;
        const double item_d = rng_.Uniform(0.12, depth - 0.04);
        const TextureStyle style =
            upright_books || rng_.Chance(0.5) ? TextureStyle::kLabel : TextureStyle::kCollage;
        Box(base * Pose(x + 0.5 * item_w,
                        0.02 + 0.5 * item_d + rng_.Uniform(0.0, depth - 0.04 - item_d),
                        z + 0.5 * board + 0.5 * item_h, rng_.Uniform(-0.08, 0.08)),
            {item_w, item_d, item_h}, kFurnitureDensity, style, 0, RandomColour(0.2, 1.0));
        x += item_w + (upright_books ? rng_.Uniform(0.0, 0.01) : rng_.Uniform(0.02, 0.12));
      }
    }
  }

  void AddShelves() {
    const Eigen::Vector3d& lo = layout_.min;
    const Eigen::Vector3d& hi = layout_.max;
    // Back wall: three units behind the table, facing the standard viewpoint.
    for (const double x : {-1.55, 0.0, 1.55}) {
      ShelfUnit(Pose(x + rng_.Uniform(-0.1, 0.1), hi.y(), 0.0, M_PI), 1.0, rng_.Uniform(1.75, 2.0),
                5);
    }
    // Side walls: a unit on each, between the actors' two lanes.
    ShelfUnit(Pose(lo.x(), 0.2, 0.0, -0.5 * M_PI), 1.0, 1.9, 5);
    ShelfUnit(Pose(hi.x(), 0.2, 0.0, 0.5 * M_PI), 1.0, 1.6, 4);
    // Front wall, behind the standard viewpoint: a unit and a door.
    ShelfUnit(Pose(-1.2, lo.y(), 0.0, 0.0), 1.2, 1.9, 5);
    Box(Pose(1.4, lo.y() + 0.025, 1.02), {0.9, 0.05, 2.04}, kFurnitureDensity, TextureStyle::kWood);
  }

  void AddFloorClutter() {
    const Eigen::Vector3d& lo = layout_.min;
    const Eigen::Vector3d& hi = layout_.max;
    // Stacks of boxes in the four corners, clear of the actors' lanes and exits.
    const Eigen::Vector2d corners[] = {{lo.x() + 0.45, lo.y() + 0.45},
                                       {hi.x() - 0.45, lo.y() + 0.45},
                                       {lo.x() + 0.45, hi.y() - 0.3},
                                       {hi.x() - 0.45, hi.y() - 0.3}};
    for (const Eigen::Vector2d& corner : corners) {
      double z = 0.0;
      for (int k = rng_.UniformInt(1, 3); k > 0; --k) {
        const Eigen::Vector3d size(rng_.Uniform(0.3, 0.55), rng_.Uniform(0.25, 0.4),
                                   rng_.Uniform(0.2, 0.4));
        Box(Pose(corner.x() + rng_.Uniform(-0.05, 0.05), corner.y() + rng_.Uniform(-0.05, 0.05),
                 z + 0.5 * size.z(), rng_.Uniform(-0.3, 0.3)),
            size, kFurnitureDensity,
            rng_.Chance(0.5) ? TextureStyle::kLabel : TextureStyle::kCollage, 0,
            RandomColour(0.3, 0.9));
        z += size.z();
      }
    }
  }

  int NextInstance(const std::string& class_name, int coco_id) {
    const int id = kFirstObjectInstanceId + static_cast<int>(scene_.instances.size());
    scene_.instances.push_back({id, class_name, coco_id});
    return id;
  }

  void AddKeyObjects() {
    const double top = layout_.table_height;
    const auto jitter = [&](double amount) { return rng_.Uniform(-amount, amount); };

    // Laptop: base and a screen tilted back 15 degrees, facing the standard viewpoint.
    {
      const int id = NextInstance("laptop", CocoClassId("laptop"));
      const SE3 base = Pose(-0.38 + jitter(0.04), 0.05 + jitter(0.03), top, jitter(0.15));
      Box(base * Pose(0, 0, 0.009), {0.34, 0.24, 0.018}, kObjectDensity, TextureStyle::kKeyboard,
          id);
      const SE3 hinge = base * Pose(0, 0.115, 0.018);
      const SE3 tilt(Eigen::Matrix3d(Eigen::AngleAxisd(-0.26, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d::Zero());
      Box(hinge * tilt * Pose(0, 0.004, 0.115), {0.34, 0.008, 0.23}, kObjectDensity,
          TextureStyle::kCollage, id);
    }
    // Keyboard and mouse in front of the laptop's right.
    {
      const int id = NextInstance("keyboard", CocoClassId("keyboard"));
      Box(Pose(0.2 + jitter(0.04), -0.22 + jitter(0.03), top + 0.0125, jitter(0.12)),
          {0.44, 0.14, 0.025}, kObjectDensity, TextureStyle::kKeyboard, id);
    }
    {
      const int id = NextInstance("mouse", CocoClassId("mouse"));
      Box(Pose(0.53 + jitter(0.03), -0.2 + jitter(0.03), top + 0.0175, jitter(0.3)),
          {0.06, 0.1, 0.035}, kObjectDensity, TextureStyle::kLabel, id, RandomColour(0.1, 0.6));
    }
    // Cup (with a handle) and bottle.
    {
      const int id = NextInstance("cup", CocoClassId("cup"));
      const SE3 base = Pose(0.05 + jitter(0.05), 0.2 + jitter(0.03), top, jitter(M_PI));
      LabelledCylinder(base, 0.04, 0.1, id, RandomColour(0.5, 1.0));
      Box(base * Pose(0.05, 0, 0.05), {0.02, 0.012, 0.06}, kObjectDensity, TextureStyle::kLabel, id,
          RandomColour(0.5, 1.0));
    }
    {
      const int id = NextInstance("bottle", CocoClassId("bottle"));
      const SE3 base = Pose(-0.08 + jitter(0.04), 0.32 + jitter(0.03), top, jitter(M_PI));
      const SurfaceTag tag = LabelledCylinder(base, 0.035, 0.2, id, RandomColour(0.3, 1.0));
      AddCylinder(base * Pose(0, 0, 0.2), 0.015, 0.06, 12, tag, &scene_.triangles);
    }
    // Books: a stack of two on the right, one lying askew on the left.
    {
      const int id = NextInstance("book", CocoClassId("book"));
      const SE3 base = Pose(0.55 + jitter(0.03), 0.18 + jitter(0.03), top, jitter(0.3));
      Box(base * Pose(0, 0, 0.015), {0.17, 0.24, 0.03}, kObjectDensity, TextureStyle::kLabel, id,
          RandomColour(0.3, 1.0));
      const int second = NextInstance("book", CocoClassId("book"));
      Box(base * Pose(jitter(0.02), jitter(0.02), 0.0425, jitter(0.3)), {0.15, 0.22, 0.025},
          kObjectDensity, TextureStyle::kLabel, second, RandomColour(0.3, 1.0));
    }
    {
      const int id = NextInstance("book", CocoClassId("book"));
      Box(Pose(-0.66 + jitter(0.03), -0.26 + jitter(0.03), top + 0.02, -0.35 + jitter(0.2)),
          {0.2, 0.27, 0.04}, kObjectDensity, TextureStyle::kLabel, id, RandomColour(0.3, 1.0));
    }
  }

  const RoomLayout& layout_;
  uint64_t seed_;
  Random rng_;
  TextureBank* bank_;
  StaticScene scene_;
};

}  // namespace

StaticScene BuildStaticScene(const RoomLayout& layout, uint64_t seed, TextureBank* bank) {
  return Builder(layout, seed, bank).Build();
}

}  // namespace drvslam::synth
