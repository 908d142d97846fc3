#include "drvslam/tools/synth/actors.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drvslam/core/error.h"
#include "drvslam/tools/synth/actor_routes.h"
#include "drvslam/tools/synth/billboard.h"
#include "drvslam/tools/synth/random.h"

namespace drvslam::synth {
namespace {

constexpr double kStride = 1.3;            // metres per full gait cycle (two steps)
constexpr double kTurnRate = 2.5;          // rad/s, turning on the spot
constexpr double kSteerRate = 3.0;         // rad/s, while walking
constexpr double kTurnOnSpot = 0.6;        // rad: sharper turns stop the walk first
constexpr double kGaitRate = 4.0;          // 1/s: how fast the gait starts and stops
constexpr double kPersonalSpace = 0.7;     // metres kept from another actor
constexpr double kCameraClearance = 0.75;  // metres kept from the camera (horizontally)
constexpr double kGiveUpWait = 3.0;        // longest wait (s) when blocked, then turn back
constexpr double kSitTransition = 0.9;     // seconds to sit down or stand up
constexpr double kSitProbability = 0.25;   // at a free stool
constexpr double kPauseProbability = 0.3;  // standing a while at a lane node
constexpr double kExitWeight = 0.3;        // relative chance of heading for an exit
constexpr double kFrontWeight = 1.6;       // ... and for the lane in front of the table
constexpr double kPassWeight = 0.5;        // ... and for the detour close to the camera
constexpr double kTexelDensity = 400.0;

constexpr double kTwoPi = 2.0 * M_PI;

double WrapAngle(double angle) { return std::remainder(angle, kTwoPi); }

using routes::BuildRoutes;
using routes::Node;
using routes::NodeKind;
using routes::RouteGraph;

// Small motions of a seated or standing person: slow sway (too slow to count as moving) and
// episodes of gesturing, twisting, looking around or leaning forward.
struct Fidget {
  struct Episode {
    double start, duration;
    int kind;
    double sign;
    int side;
  };
  double phase[4] = {0, 0, 0, 0};
  std::vector<Episode> episodes;

  static Fidget Make(Random& rng, double duration) {
    Fidget f;
    for (double& p : f.phase) p = rng.Uniform(0.0, kTwoPi);
    double t = rng.Uniform(0.3, 3.0);
    while (t < duration) {
      Episode e{t, rng.Uniform(1.0, 2.5), rng.UniformInt(0, 3), rng.Chance(0.5) ? 1.0 : -1.0,
                rng.UniformInt(0, 1)};
      f.episodes.push_back(e);
      t += e.duration + rng.Uniform(1.0, 5.0);
    }
    return f;
  }

  void Apply(double t, PersonPose* pose) const {
    pose->torso_lean += 0.03 * std::sin(kTwoPi * t / 5.3 + phase[0]);
    pose->head_yaw += 0.15 * std::sin(kTwoPi * t / 6.1 + phase[1]);
    pose->head_pitch += 0.05 * std::sin(kTwoPi * t / 4.7 + phase[2]);
    pose->torso_twist += 0.03 * std::sin(kTwoPi * t / 7.9 + phase[3]);
    for (const Episode& e : episodes) {
      if (t < e.start || t >= e.start + e.duration) continue;
      const double tau = t - e.start;
      const double s = std::sin(M_PI * tau / e.duration);
      const double envelope = s * s;
      switch (e.kind) {
        case 0:  // gesture with one arm
          pose->arm_swing[e.side] += envelope * (0.9 + 0.3 * std::sin(kTwoPi * 1.1 * tau));
          pose->elbow[e.side] += envelope * 0.5;
          pose->arm_raise[e.side] += envelope * 0.3;
          break;
        case 1:
          pose->torso_twist += envelope * 0.5 * e.sign;
          break;
        case 2:
          pose->head_yaw += envelope * 0.9 * e.sign;
          pose->head_pitch += envelope * 0.2;
          break;
        default:
          pose->torso_lean += envelope * 0.3;
          break;
      }
    }
  }
};

PersonPose GaitPose(double phase, double gait, double sit) {
  PersonPose pose;
  pose.sit = sit;
  const double s = std::sin(phase);
  pose.leg_swing = {0.4 * gait * s, -0.4 * gait * s};
  pose.knee = {0.5 * gait * std::max(0.0, std::sin(phase + 0.6)),
               0.5 * gait * std::max(0.0, std::sin(phase + M_PI + 0.6))};
  pose.arm_swing = {-0.35 * gait * s + 0.5 * sit, 0.35 * gait * s + 0.5 * sit};
  pose.elbow = {0.15 + 0.15 * gait + 0.9 * sit, 0.15 + 0.15 * gait + 0.9 * sit};
  pose.arm_raise = {0.04, 0.04};
  return pose;
}

struct Walker {
  enum class Mode { kPause, kWalk, kTurn, kSitDown, kSeated, kStandUp };
  Mode mode = Mode::kPause;
  Mode after_turn = Mode::kWalk;
  int previous = -1, from = 0, to = 0;
  double timer = 0.0, wait = 0.0;
  // How long to wait when blocked before giving way; drawn anew each time, so that two
  // walkers blocking each other do not both give way at once.
  double patience = kGiveUpWait;
  double base_speed = 1.0, speed = 1.0;
  double target_heading = 0.0;
  double phase = 0.0, gait = 0.0, sit = 0.0;
  Eigen::Vector2d position{0, 0};
  double heading = 0.0;
  Fidget fidget;
  bool always_fidgets = false;
};

class Simulation {
 public:
  Simulation(const RoomLayout& layout, ActorBehaviour behaviour, int count, Random* rng,
             uint64_t seed, double duration)
      : graph_(BuildRoutes(layout)), rng_(*rng), seat_owner_(layout.stools.size(), -1) {
    walkers_.resize(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      walkers_[k].base_speed = rng_.Uniform(0.6, 1.4);
      // Each actor's small motions come from a stream of its own, so that a longer sequence
      // (more episodes drawn) starts exactly like a shorter one.
      Random fidget_rng(SubSeed(seed, RandomStream::kActors, 1000 + static_cast<uint64_t>(k)));
      walkers_[k].fidget = Fidget::Make(fidget_rng, duration + 1.0);
    }
    if (behaviour == ActorBehaviour::kSitting) {
      PlaceSitters(layout);
    } else {
      PlaceWalkers();
    }
  }

  const std::vector<Walker>& Walkers() const { return walkers_; }

  void Step(double dt, const Eigen::Vector2d& camera) {
    std::vector<Eigen::Vector2d> positions;
    for (const Walker& w : walkers_) positions.push_back(w.position);
    for (int k = 0; k < static_cast<int>(walkers_.size()); ++k) Step(k, dt, camera, positions);
  }

  ActorState StateOf(int k, double t) const {
    const Walker& w = walkers_[k];
    ActorState state;
    state.position = w.position;
    state.heading = w.heading;
    state.pose = GaitPose(w.phase, w.gait, w.sit);
    if (w.always_fidgets || w.mode == Walker::Mode::kSeated) w.fidget.Apply(t, &state.pose);
    return state;
  }

 private:
  void PlaceSitters(const RoomLayout& layout) {
    int standing = 0;
    for (int k = 0; k < static_cast<int>(walkers_.size()); ++k) {
      Walker& w = walkers_[k];
      w.always_fidgets = true;
      w.timer = std::numeric_limits<double>::infinity();
      w.heading = -0.5 * M_PI;  // facing the standard viewpoint across the table
      if (k < static_cast<int>(layout.stools.size())) {
        w.position = layout.stools[k];
        w.sit = 1.0;
        w.mode = Walker::Mode::kSeated;
      } else {
        // More sitters than stools: the rest stand behind, between the stools and the shelves.
        const double side = standing % 2 == 0 ? -1.0 : 1.0;
        w.position = {side * (1.1 + 0.7 * (standing / 2)), 1.3};
        w.mode = Walker::Mode::kPause;
        ++standing;
      }
    }
  }

  void PlaceWalkers() {
    std::vector<int> starts;
    for (int n = 0; n < static_cast<int>(graph_.nodes.size()); ++n) {
      if (graph_.nodes[n].kind != NodeKind::kSeat) starts.push_back(n);
    }
    // A seeded shuffle, so that walkers start at distinct places.
    for (int i = static_cast<int>(starts.size()) - 1; i > 0; --i) {
      std::swap(starts[i], starts[rng_.UniformInt(0, i)]);
    }
    for (int k = 0; k < static_cast<int>(walkers_.size()); ++k) {
      Walker& w = walkers_[k];
      w.from = w.to = starts[k % starts.size()];
      w.position = graph_.nodes[w.from].p;
      if (k >= static_cast<int>(starts.size())) {
        w.position += Eigen::Vector2d(0.3 * (k / starts.size()), 0.0);
      }
      const int toward = rng_.Pick(graph_.next[w.from]);
      const Eigen::Vector2d d = graph_.nodes[toward].p - w.position;
      w.heading = std::atan2(d.y(), d.x());
      w.mode = Walker::Mode::kPause;
      w.timer = rng_.Uniform(0.0, 1.5);
    }
  }

  void ChooseNext(Walker& w) {
    // Exits are chosen less often than lanes, so that people are in view most of the time, as
    // in the real walking sequences; turning straight back only at a dead end.
    std::vector<int> options;
    std::vector<double> weights;
    for (int pass = 0; pass < 2 && options.empty(); ++pass) {
      for (const int n : graph_.next[w.from]) {
        if (graph_.nodes[n].kind == NodeKind::kSeat || (pass == 0 && n == w.previous)) continue;
        options.push_back(n);
        const Node& node = graph_.nodes[n];
        weights.push_back(node.kind == NodeKind::kExit ? kExitWeight
                          : node.p.y() < 0.0           ? kFrontWeight
                                                       : 1.0);
      }
    }
    double total = 0.0;
    for (const double weight : weights) total += weight;
    double pick = rng_.Uniform(0.0, total);
    std::size_t chosen = 0;
    while (chosen + 1 < options.size() && pick >= weights[chosen]) pick -= weights[chosen++];
    w.to = options[chosen];
    w.speed = std::clamp(w.base_speed * rng_.Uniform(0.85, 1.15), 0.5, 1.5);
    w.mode = Walker::Mode::kWalk;
  }

  void Arrive(int k) {
    Walker& w = walkers_[k];
    w.previous = w.from;
    w.from = w.to;
    const Node& node = graph_.nodes[w.from];
    switch (node.kind) {
      case NodeKind::kExit:
        w.mode = Walker::Mode::kPause;
        w.timer = rng_.Uniform(0.3, 1.5);
        return;
      case NodeKind::kSeat:
        w.target_heading = -0.5 * M_PI;
        w.mode = Walker::Mode::kTurn;
        w.after_turn = Walker::Mode::kSitDown;
        return;
      case NodeKind::kApproach:
        if (w.previous != node.partner && seat_owner_[node.stool] < 0 &&
            rng_.Chance(kSitProbability)) {
          seat_owner_[node.stool] = k;
          w.to = node.partner;
          w.speed = 0.5;
          w.mode = Walker::Mode::kWalk;
          return;
        }
        break;
      case NodeKind::kPass:
        break;
      case NodeKind::kLane:
        if (rng_.Chance(kPauseProbability)) {
          w.mode = Walker::Mode::kPause;
          w.timer = rng_.Uniform(0.5, 3.0);
          return;
        }
        break;
    }
    ChooseNext(w);
  }

  void Turn(Walker& w, double dt) {
    const double diff = WrapAngle(w.target_heading - w.heading);
    if (std::fabs(diff) <= kTurnRate * dt) {
      w.heading = w.target_heading;
      w.mode = w.after_turn;
    } else {
      w.heading = WrapAngle(w.heading + std::copysign(kTurnRate * dt, diff));
    }
  }

  bool Blocked(int k, const Eigen::Vector2d& next, const Eigen::Vector2d& camera,
               const std::vector<Eigen::Vector2d>& positions) const {
    const Walker& w = walkers_[k];
    const auto closing = [&](const Eigen::Vector2d& other, double clearance) {
      const double after = (next - other).norm();
      return after < clearance && after < (w.position - other).norm();
    };
    for (int j = 0; j < static_cast<int>(positions.size()); ++j) {
      if (j != k && closing(positions[j], kPersonalSpace)) return true;
    }
    return closing(camera, kCameraClearance);
  }

  void Walk(int k, double dt, const Eigen::Vector2d& camera,
            const std::vector<Eigen::Vector2d>& positions) {
    Walker& w = walkers_[k];
    const Eigen::Vector2d target = graph_.nodes[w.to].p;
    const Eigen::Vector2d delta = target - w.position;
    const double distance = delta.norm();
    if (distance < 1e-9) {
      Arrive(k);
      return;
    }
    const double desired = std::atan2(delta.y(), delta.x());
    const double diff = WrapAngle(desired - w.heading);
    if (std::fabs(diff) > kTurnOnSpot) {
      w.target_heading = desired;
      w.after_turn = Walker::Mode::kWalk;
      w.mode = Walker::Mode::kTurn;
      Turn(w, dt);
      return;
    }
    w.heading = WrapAngle(w.heading + std::clamp(diff, -kSteerRate * dt, kSteerRate * dt));
    const double step = std::min(w.speed * dt, distance);
    const Eigen::Vector2d next = w.position + delta * (step / distance);
    if (Blocked(k, next, camera, positions)) {
      if (w.wait == 0.0) w.patience = rng_.Uniform(0.5, 1.0) * kGiveUpWait;
      w.wait += dt;
      w.gait = std::max(0.0, w.gait - kGaitRate * dt);
      if (w.wait > w.patience) {
        // Give way: head back where it came from (and give up a stool it was heading for).
        if (graph_.nodes[w.to].kind == NodeKind::kSeat) seat_owner_[graph_.nodes[w.to].stool] = -1;
        std::swap(w.from, w.to);
        w.previous = -1;
        w.wait = 0.0;
      }
      return;
    }
    w.wait = 0.0;
    w.position = next;
    w.phase = std::fmod(w.phase + kTwoPi * step / kStride, kTwoPi);
    w.gait = std::min(1.0, w.gait + kGaitRate * dt);
    if (step >= distance) {
      w.position = target;
      Arrive(k);
    }
  }

  void Step(int k, double dt, const Eigen::Vector2d& camera,
            const std::vector<Eigen::Vector2d>& positions) {
    Walker& w = walkers_[k];
    if (w.mode != Walker::Mode::kWalk) w.gait = std::max(0.0, w.gait - kGaitRate * dt);
    switch (w.mode) {
      case Walker::Mode::kPause:
        w.timer -= dt;
        if (w.timer <= 0.0) ChooseNext(w);
        break;
      case Walker::Mode::kTurn:
        Turn(w, dt);
        break;
      case Walker::Mode::kWalk:
        Walk(k, dt, camera, positions);
        break;
      case Walker::Mode::kSitDown:
        w.sit = std::min(1.0, w.sit + dt / kSitTransition);
        if (w.sit >= 1.0) {
          w.mode = Walker::Mode::kSeated;
          w.timer = rng_.Uniform(2.0, 5.0);
        }
        break;
      case Walker::Mode::kSeated:
        w.timer -= dt;
        if (w.timer <= 0.0) w.mode = Walker::Mode::kStandUp;
        break;
      case Walker::Mode::kStandUp:
        w.sit = std::max(0.0, w.sit - dt / kSitTransition);
        if (w.sit <= 0.0) {
          seat_owner_[graph_.nodes[w.from].stool] = -1;
          w.previous = -1;
          w.to = graph_.nodes[w.from].partner;
          w.speed = 0.5;
          w.mode = Walker::Mode::kWalk;
        }
        break;
    }
  }

  RouteGraph graph_;
  Random& rng_;
  std::vector<int> seat_owner_;
  std::vector<Walker> walkers_;
};

// Textures of one box person: shirt, skin and trousers in colours of its own.
PersonBody MakeBody(double height, double seat_height, uint64_t seed, int actor,
                    TextureBank* bank) {
  Random rng(SubSeed(seed, RandomStream::kActorTextures, static_cast<uint64_t>(actor)));
  PersonBody body;
  body.height = height;
  body.seat_height = seat_height;
  static const cv::Vec3b kSkinTones[] = {
      {175, 195, 235}, {130, 165, 215}, {95, 135, 190}, {60, 90, 135}};
  const cv::Vec3b skin = kSkinTones[rng.UniformInt(0, 3)];
  const auto colour = [&](double lo, double hi) {
    return cv::Vec3b(static_cast<uint8_t>(rng.Uniform(lo, hi)),
                     static_cast<uint8_t>(rng.Uniform(lo, hi)),
                     static_cast<uint8_t>(rng.Uniform(lo, hi)));
  };
  const cv::Vec3b shirt = colour(30, 240);
  const cv::Vec3b trousers = colour(20, 120);
  const auto request = [&](BodyPart part, TextureStyle style, const cv::Vec3b& tint) {
    const Eigen::Vector2d atlas = BoxAtlasSize(body.PartSize(part));
    TextureRequest r;
    r.width_m = atlas.x();
    r.height_m = atlas.y();
    r.texels_per_metre = kTexelDensity;
    r.style = style;
    r.colour = tint;
    r.seed = rng.Bits();
    if (part == BodyPart::kHead) {
      const UvRect face = BoxAtlasFace(body.PartSize(part), 2);
      r.face_rect = cv::Rect2d(face.u0, face.v0, face.u1 - face.u0, face.v1 - face.v0);
    }
    body.textures[static_cast<int>(part)] = bank->Add(r);
  };
  request(BodyPart::kTorso, TextureStyle::kCloth, shirt);
  request(BodyPart::kHead, TextureStyle::kSkin, skin);
  request(BodyPart::kUpperArm, TextureStyle::kCloth, shirt);
  request(BodyPart::kForearm, TextureStyle::kSkin, skin);
  request(BodyPart::kThigh, TextureStyle::kCloth, trousers);
  request(BodyPart::kShin, TextureStyle::kCloth, trousers);
  return body;
}

// A cart's crate: packaging print, in a colour of its own.
int CartTexture(uint64_t seed, int actor, TextureBank* bank) {
  Random rng(SubSeed(seed, RandomStream::kCartTextures, static_cast<uint64_t>(actor)));
  const Eigen::Vector2d atlas = BoxAtlasSize(Eigen::Vector3d(kCartWidth, kCartLength, kCartHeight));
  TextureRequest r;
  r.width_m = atlas.x();
  r.height_m = atlas.y();
  r.texels_per_metre = kTexelDensity;
  r.style = TextureStyle::kLabel;
  r.colour = cv::Vec3b(static_cast<uint8_t>(rng.Uniform(40, 220)),
                       static_cast<uint8_t>(rng.Uniform(40, 220)),
                       static_cast<uint8_t>(rng.Uniform(40, 220)));
  r.seed = rng.Bits();
  return bank->Add(r);
}

// The cart at its state: a crate standing on the floor, its long side along the heading. Only
// position and heading count; a walker's pose does not.
void AppendCart(int texture, const ActorState& state, int instance_id, TriangleList* out) {
  const Eigen::Matrix3d R(Eigen::AngleAxisd(state.heading - 0.5 * M_PI, Eigen::Vector3d::UnitZ()));
  const SE3 pose(R, Eigen::Vector3d(state.position.x(), state.position.y(), 0.5 * kCartHeight));
  AddBox(pose, Eigen::Vector3d(kCartWidth, kCartLength, kCartHeight), {texture, instance_id, false},
         out);
}

}  // namespace

ActorSet::ActorSet(const ActorOptions& options, const RoomLayout& layout,
                   const std::vector<double>& frame_times,
                   const std::vector<Eigen::Vector3d>& camera_positions, TextureBank* bank)
    : frame_count_(static_cast<int>(frame_times.size())) {
  if (options.count < 0) throw Error("actors: count must not be negative");
  if (camera_positions.size() != frame_times.size()) {
    throw Error("actors: one camera position per frame is needed");
  }
  if (options.billboard_count > 0 && options.billboards.empty()) {
    throw Error("actors: billboard actors need at least one billboard image");
  }
  if (options.count == 0 || frame_times.empty()) return;
  const double dt = frame_times.size() > 1 ? frame_times[1] - frame_times[0] : 1.0 / 30.0;
  const double duration = frame_times.back() - frame_times.front();

  Random rng(SubSeed(options.seed, RandomStream::kActors));
  for (int k = 0; k < options.count; ++k) {
    Actor actor;
    actor.instance_id = k + 1;
    actor.class_name = options.class_name;
    actor.coco_id = options.coco_id;
    const double height = rng.Uniform(1.6, 1.85);
    if (options.shape == ActorShape::kCart) {
      actor.cart_texture = CartTexture(options.seed, k, bank);
    } else {
      actor.body = MakeBody(height, layout.stool_height, options.seed, k, bank);
    }
    if (options.shape == ActorShape::kPerson && k < options.billboard_count) {
      const cv::Mat& image = options.billboards[k % options.billboards.size()];
      actor.billboard_texture = bank->AddImage(image);
      actor.billboard_width = height * image.cols / image.rows;
    }
    actors_.push_back(std::move(actor));
  }

  camera_positions_.reserve(frame_times.size() + 1);
  camera_positions_.push_back(camera_positions.front());
  camera_positions_.insert(camera_positions_.end(), camera_positions.begin(),
                           camera_positions.end());

  Simulation simulation(layout, options.behaviour, options.count, &rng, options.seed, duration);
  for (int f = -1; f < frame_count_; ++f) {
    const double t = f < 0 ? frame_times.front() - dt : frame_times[f];
    if (f >= 0) simulation.Step(dt, camera_positions_[f + 1].head<2>());
    for (int k = 0; k < options.count; ++k) actors_[k].states.push_back(simulation.StateOf(k, t));
  }

  displacement_.assign(actors_.size(), std::vector<double>(frame_times.size(), 0.0));
  for (int k = 0; k < Count(); ++k) {
    TriangleList previous = Triangles(k, -1);
    for (int f = 0; f < frame_count_; ++f) {
      TriangleList current = Triangles(k, f);
      double largest = 0.0;
      for (std::size_t i = 0; i < current.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          largest = std::max(largest, (current[i].p[c] - previous[i].p[c]).norm());
        }
      }
      displacement_[k][f] = largest;
      previous = std::move(current);
    }
  }
}

const ActorState& ActorSet::State(int actor, int frame) const {
  return actors_[actor].states[static_cast<std::size_t>(frame + 1)];
}

TriangleList ActorSet::Triangles(int actor, int frame) const {
  TriangleList out;
  const Actor& a = actors_[actor];
  const ActorState& s = State(actor, frame);
  if (a.cart_texture >= 0) {
    AppendCart(a.cart_texture, s, a.instance_id, &out);
    return out;
  }
  if (a.billboard_texture >= 0) {
    const Eigen::Vector3d& camera = camera_positions_[static_cast<std::size_t>(frame + 1)];
    Eigen::Vector2d facing = camera.head<2>() - s.position;
    if (facing.norm() < 1e-6) facing = Eigen::Vector2d(std::cos(s.heading), std::sin(s.heading));
    facing.normalize();
    const Eigen::Vector2d side(-facing.y(), facing.x());
    BillboardPlacement placement;
    placement.base = Eigen::Vector3d(s.position.x(), s.position.y(), 0.0);
    placement.facing = facing;
    // Small motions lean the cut-out: forward lean towards the camera, twist and head sideways.
    placement.sway = facing * (0.8 * s.pose.torso_lean) +
                     side * (0.3 * s.pose.torso_twist + 0.1 * s.pose.head_yaw +
                             0.15 * (s.pose.arm_swing[1] - s.pose.arm_swing[0]));
    AppendBillboard(a.billboard_texture, a.billboard_width, a.body.height, placement, a.instance_id,
                    &out);
    return out;
  }
  // The person model faces its +y axis; heading is the world angle of the facing direction.
  const SE3 T_world_person(
      Eigen::Matrix3d(Eigen::AngleAxisd(s.heading - 0.5 * M_PI, Eigen::Vector3d::UnitZ())),
      Eigen::Vector3d(s.position.x(), s.position.y(), 0.0));
  AppendPerson(a.body, s.pose, T_world_person, a.instance_id, &out);
  return out;
}

void ActorSet::AppendTriangles(int frame, TriangleList* out) const {
  for (int k = 0; k < Count(); ++k) {
    const TriangleList triangles = Triangles(k, frame);
    out->insert(out->end(), triangles.begin(), triangles.end());
  }
}

void ActorSet::AppendTrianglesAt(double frame_position, TriangleList* out) const {
  if (Count() == 0) return;
  const double base = std::floor(frame_position);
  if (base == frame_position && base >= -1.0 && base < frame_count_) {
    AppendTriangles(static_cast<int>(base), out);
    return;
  }
  // Simulated states cover frames -1 .. frame_count_ - 1.
  const int a = static_cast<int>(std::clamp(base, -1.0, frame_count_ - 2.0));
  const double weight = frame_position - a;
  for (int k = 0; k < Count(); ++k) {
    TriangleList triangles = Triangles(k, a);
    const TriangleList next = Triangles(k, a + 1);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        triangles[i].p[c] += weight * (next[i].p[c] - triangles[i].p[c]);
      }
    }
    out->insert(out->end(), triangles.begin(), triangles.end());
  }
}

std::vector<SynthInstance> ActorSet::Instances() const {
  std::vector<SynthInstance> instances;
  for (const Actor& a : actors_) instances.push_back({a.instance_id, a.class_name, a.coco_id});
  return instances;
}

}  // namespace drvslam::synth
