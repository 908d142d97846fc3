// CameraPath: where the camera is at any time. Procedural paths mirror the TUM dynamic
// sequences' camera motions around the standard viewpoint (xyz translations, roll-pitch-yaw
// rotations, a half-sphere sweep, a near-static hand-held camera); a replayed path takes a real
// TUM ground-truth trajectory and re-anchors it in the synthetic room, keeping its motion exact
// (it is moved and turned rigidly about the vertical, never bent or scaled).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/synth/room_layout.h"

namespace drvslam::synth {

enum class PathKind { kXyz, kStatic, kRpy, kHalfsphere, kReplay, kCircuit };

// "xyz", "static", "rpy", "halfsphere", "replay", "circuit".
std::string PathKindName(PathKind kind);

class CameraPath {
 public:
  static constexpr double kCircuitRadius = 0.6;   // metres
  static constexpr double kCircuitPeriod = 12.0;  // seconds per turn

  // Smooth closed-form motion around `anchor`, with hand shake; the seed picks phases and
  // shake, so a dynamic scenario and its static counterpart share one path.
  //  xyz: translations along the camera's axes (about +-0.3, 0.2, 0.25 m);
  //  rpy: rotations about the camera centre (yaw +-25, pitch +-15, roll +-15 degrees);
  //  halfsphere: the centre sweeps a half-sphere of 1 m diameter behind the anchor while the
  //    camera keeps looking at the anchor's target;
  //  static: the anchor held by hand (a few mm and a few tenths of a degree of shake);
  //  circuit: the centre circles the anchor's target (radius kCircuitRadius, at 1.3 m)
  //    looking outwards and 20 degrees down, one turn every kCircuitPeriod seconds, so the
  //    views of the start come back after every other wall (a loop for loop closing).
  static CameraPath Procedural(PathKind kind, const ViewAnchor& anchor, uint64_t seed);

  // Replays `recorded` (camera-to-world, increasing stamps, at least 2 poses). The recorded
  // world's up is found from the cameras (their image rows stay level; a result near a
  // coordinate axis snaps to it), so TUM ground truth (z up) and odometry output in its first
  // camera's frame both come out upright.
  // The path is then turned about the vertical and shifted horizontally so that the point the
  // cameras look at most (least-squares meeting point of the optical axes) lands on the
  // anchor's target and the first camera sees it from the anchor's side. Heights of a z-up
  // recording are kept (TUM's origin is on the floor); otherwise the first camera is put at the
  // anchor's height.
  static CameraPath Replay(const Trajectory& recorded, const ViewAnchor& anchor);

  PathKind Kind() const { return kind_; }
  // Camera-to-world pose at t seconds after the start. Replayed paths interpolate between
  // recorded poses (slerp for rotation, linear for translation) and hold the end poses
  // outside the recording.
  SE3 PoseAt(double t) const;
  // Length of a replayed recording in seconds; infinity for procedural paths.
  double Duration() const;
  // First recorded stamp of a replay; 0 for procedural paths.
  double RecordedStart() const { return recorded_start_; }

 private:
  PathKind kind_ = PathKind::kStatic;
  ViewAnchor anchor_;
  SE3 anchor_pose_;
  // Procedural: phases and shake parameters.
  double phase_[6] = {0, 0, 0, 0, 0, 0};
  double shake_frequency_[6][3] = {};
  double shake_phase_[6][3] = {};
  // Replay: anchored poses at times relative to the first stamp.
  std::vector<double> times_;
  std::vector<SE3> poses_;
  double recorded_start_ = 0.0;
};

}  // namespace drvslam::synth
