// Actors: the potentially-moving objects of a scenario (people by default, or pushed carts).
// Walkers roam a graph of lanes around the table at 0.5 to 1.5 m/s - turning, pausing, leaving the
// view through the room's sides, coming back, sometimes sitting down on a stool - and wait rather
// than walk into each other or the camera. Sitters stay seated (or standing) with the small motions
// of TUM's sitting sequences: slow sway, and now and then a gesture, a turn or a look around.
// Everything is simulated once, frame by frame, from the seed; an actor's geometry at a frame is
// then a pure function of its stored state. A cart is pushed along the walkers' lanes by someone
// out of view: it moves as a walker would, rigidly, and waits where a walker would sit.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/tools/synth/instances_file.h"
#include "drvslam/tools/synth/person_model.h"
#include "drvslam/tools/synth/room_layout.h"
#include "drvslam/tools/synth/scene.h"
#include "drvslam/tools/synth/texture_bank.h"

namespace drvslam::synth {

// An actor is "moving" in a frame when some corner of its geometry moved more than this
// (metres) since the previous frame (0.3 m/s at 30 Hz): walking always is, a gesture usually
// is, slow swaying and standing still are not.
inline constexpr double kMovingThreshold = 0.01;

enum class ActorBehaviour { kWalking, kSitting };
enum class ActorShape { kPerson, kCart };

// A cart: a crate pushed across the floor, about waist high (length along its heading, width,
// height).
inline constexpr double kCartLength = 0.8;
inline constexpr double kCartWidth = 0.55;
inline constexpr double kCartHeight = 0.95;

struct ActorOptions {
  int count = 2;
  ActorBehaviour behaviour = ActorBehaviour::kWalking;
  ActorShape shape = ActorShape::kPerson;  // carts are never billboards
  std::string class_name = "person";
  int coco_id = 0;
  // Cut-out images (CV_8UC4); the first billboard_count actors use them in turn.
  std::vector<cv::Mat> billboards;
  int billboard_count = 0;
  uint64_t seed = 1;
};

struct ActorState {
  Eigen::Vector2d position{0, 0};  // floor position (world x, y)
  double heading = 0.0;            // facing direction (cos, sin) in the world
  PersonPose pose;
};

class ActorSet {
 public:
  ActorSet() = default;
  // Creates the actors (queueing their textures in `bank`) and simulates them at
  // `frame_times` (seconds from the first frame, evenly spaced). camera_positions[f] is the
  // camera centre at frame f; the actors keep clear of it and billboards turn towards it.
  ActorSet(const ActorOptions& options, const RoomLayout& layout,
           const std::vector<double>& frame_times,
           const std::vector<Eigen::Vector3d>& camera_positions, TextureBank* bank);

  int Count() const { return static_cast<int>(actors_.size()); }
  int FrameCount() const { return frame_count_; }
  int InstanceId(int actor) const { return actors_[actor].instance_id; }
  bool IsBillboard(int actor) const { return actors_[actor].billboard_texture >= 0; }
  // State at `frame`; frame -1 is one frame period before the first.
  const ActorState& State(int actor, int frame) const;
  // World-frame geometry of one actor at `frame` (-1 allowed).
  TriangleList Triangles(int actor, int frame) const;
  // Appends every actor's geometry at `frame`.
  void AppendTriangles(int frame, TriangleList* out) const;
  // Appends every actor's geometry at a fractional frame position (frame + a fraction of the
  // frame period), for renders between frames (motion blur, rolling shutter): each corner moves
  // linearly between the two nearest simulated frames, and past the ends of the simulation it
  // continues the first or last frame-to-frame motion. An integer position gives exactly
  // AppendTriangles.
  void AppendTrianglesAt(double frame_position, TriangleList* out) const;
  // Largest corner displacement since the previous frame, and whether it exceeds
  // kMovingThreshold.
  double Displacement(int actor, int frame) const { return displacement_[actor][frame]; }
  bool Moving(int actor, int frame) const { return displacement_[actor][frame] > kMovingThreshold; }
  std::vector<SynthInstance> Instances() const;

 private:
  struct Actor {
    int instance_id = 0;
    std::string class_name;
    int coco_id = 0;
    PersonBody body;
    int cart_texture = -1;  // a cart's crate (>= 0 for carts only)
    int billboard_texture = -1;
    double billboard_width = 0.0;
    // states[f + 1] is the state at frame f.
    std::vector<ActorState> states;
  };

  std::vector<Actor> actors_;
  std::vector<Eigen::Vector3d> camera_positions_;  // [f + 1]
  std::vector<std::vector<double>> displacement_;
  int frame_count_ = 0;
};

}  // namespace drvslam::synth
