#include "drvslam/dense/dense_mapper.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "drvslam/dense/voxel_grid.h"

namespace drvslam {
namespace {

constexpr int kMaxParentSteps = 1000;

const DenseMapOptions& Checked(const DenseMapOptions& options) {
  options.Check();
  return options;
}

}  // namespace

SE3 CurrentKeyFramePose(const KeyFrame& keyframe) {
  if (!keyframe.IsBad()) return keyframe.InversePose();
  // T_cw of a removed keyframe = T_cp * T_pw, up the spanning tree to a live ancestor.
  SE3 T_cp = keyframe.PoseRelativeToParent();
  std::shared_ptr<KeyFrame> parent = keyframe.Parent();
  for (int step = 0; parent && step < kMaxParentSteps; ++step) {
    if (!parent->IsBad()) return (T_cp * parent->Pose()).Inverse();
    T_cp = T_cp * parent->PoseRelativeToParent();
    parent = parent->Parent();
  }
  return keyframe.InversePose();
}

DenseMapper::DenseMapper(const CameraOptions& camera, const DenseMapOptions& options,
                         bool sequential, StageTimings* timings)
    : camera_(camera),
      options_(Checked(options)),
      sequential_(sequential),
      timings_(timings),
      coarse_(options.leaf_size),
      fine_(options.object_leaf_size),
      queue_(static_cast<std::size_t>(options.queue_capacity)) {
  if (!sequential_) worker_ = std::thread([this] { Run(); });
}

DenseMapper::~DenseMapper() { Shutdown(); }

void DenseMapper::Shutdown() {
  if (stopped_) return;
  stopped_ = true;
  queue_.Close();
  if (worker_.joinable()) worker_.join();
}

void DenseMapper::Run() {
  while (std::optional<Job> job = queue_.Pop()) {
    // Frames are checked when handed over; whatever else goes wrong loses one keyframe, never
    // the thread.
    try {
      Process(std::move(*job));
    } catch (const std::exception& e) {
      spdlog::error("dense mapping: keyframe left out: {}", e.what());
    }
  }
}

void DenseMapper::Process(Job job) {
  if (std::holds_alternative<ResetJob>(job)) {
    std::lock_guard<std::mutex> lock(mutex_);
    coarse_.Clear();
    fine_.Clear();
    anchors_.clear();
    ++stats_.resets;
    since_compaction_ = 0;
    return;
  }
  Integrate(std::move(std::get<KeyFrameJob>(job)));
}

void DenseMapper::MarkMoving(DenseFrame* frame) {
  bool changed = false;
  for (DenseInstance& instance : frame->instances) {
    if (instance.track_id < 0 || !instance.potentially_moving) continue;
    if (instance.moving) {
      changed |= moving_tracks_tracking_.insert(instance.track_id).second;
    } else if (options_.sticky_moving && moving_tracks_tracking_.count(instance.track_id)) {
      instance.moving = true;
    }
  }
  if (changed && options_.sticky_moving) {
    std::lock_guard<std::mutex> lock(moving_mutex_);
    moving_tracks_ = moving_tracks_tracking_;
  }
}

void DenseMapper::AddFrame(DenseFrame frame) {
  CheckDenseFrame(frame);
  MarkMoving(&frame);
  ++frames_;
  if (options_.enhancement_frames == 0) return;
  ring_.push_back(std::move(frame));
  if (ring_.size() > static_cast<std::size_t>(options_.enhancement_frames)) {
    ring_.erase(ring_.begin());
  }
}

void DenseMapper::AddKeyFrame(DenseFrame frame, std::shared_ptr<const KeyFrame> keyframe) {
  CheckDenseFrame(frame);
  MarkMoving(&frame);
  KeyFrameJob job;
  // The ring holds exactly the latest enhancement_frames frames: the nearest ones in time that
  // are known now, the same whether the job runs at once or later.
  job.neighbours = ring_;
  job.keyframe = std::move(keyframe);
  job.frame = frame;
  ++frames_;
  if (options_.enhancement_frames > 0) {
    ring_.push_back(std::move(frame));
    if (ring_.size() > static_cast<std::size_t>(options_.enhancement_frames)) {
      ring_.erase(ring_.begin());
    }
  }
  if (sequential_ || stopped_) {
    Process(std::move(job));
  } else {
    queue_.Push(std::move(job));
  }
}

void DenseMapper::Reset() {
  ring_.clear();
  if (sequential_ || stopped_) {
    Process(ResetJob{});
  } else {
    queue_.Push(ResetJob{});
  }
}

void DenseMapper::Integrate(KeyFrameJob job) {
  const Stopwatch watch;
  const DenseFrame& frame = job.frame;
  const PixelRoles roles = PaintRoles(frame, options_);
  const std::size_t mapped_pixels = CountMappedPixels(frame, roles, options_);
  const DenseCloud coarse = VoxelDownsample(
      BackProject(frame, roles, PixelRole::kBackground, camera_, options_), options_.leaf_size);

  // Key objects of the keyframe and its neighbours, in the keyframe's camera frame.
  DenseCloud objects = BackProject(frame, roles, PixelRole::kKeyObject, camera_, options_);
  std::size_t used = 0;
  const SE3 T_kw = frame.T_wc.Inverse();
  for (const DenseFrame& neighbour : job.neighbours) {
    const PixelRoles neighbour_roles = PaintRoles(neighbour, options_);
    DenseCloud points =
        BackProject(neighbour, neighbour_roles, PixelRole::kKeyObject, camera_, options_);
    if (points.empty()) continue;
    ++used;
    const SE3 T_kn = T_kw * neighbour.T_wc;
    const Eigen::Matrix3f R = T_kn.Rotation().cast<float>();
    const Eigen::Vector3f t = T_kn.Translation().cast<float>();
    for (DensePoint& p : points) p.position = R * p.position + t;
    objects.insert(objects.end(), points.begin(), points.end());
  }
  const DenseCloud fine = VoxelDownsample(objects, options_.object_leaf_size);

  const SE3 T_wa = job.keyframe ? CurrentKeyFramePose(*job.keyframe) : frame.T_wc;
  std::lock_guard<std::mutex> lock(mutex_);
  const int anchor = static_cast<int>(anchors_.size());
  anchors_.push_back({job.keyframe, frame.T_wc});
  coarse_.Insert(coarse, anchor, T_wa);
  fine_.Insert(fine, anchor, T_wa);
  ++stats_.keyframes;
  stats_.enhancement_frames += used;
  stats_.full_resolution_points += mapped_pixels;
  if (++since_compaction_ >= static_cast<std::size_t>(options_.compact_every)) CompactLocked();
  const double ms = watch.ElapsedMs();
  keyframe_ms_.push_back(ms);
  if (timings_ != nullptr) timings_->Record("dense_keyframe", ms);
}

std::vector<SE3> DenseMapper::AnchorPoses() const {
  std::vector<SE3> poses;
  poses.reserve(anchors_.size());
  for (const Anchor& anchor : anchors_) {
    poses.push_back(anchor.keyframe ? CurrentKeyFramePose(*anchor.keyframe) : anchor.T_wc);
  }
  return poses;
}

void DenseMapper::CompactLocked() {
  const std::vector<SE3> poses = AnchorPoses();
  coarse_.Rekey(poses);
  fine_.Rekey(poses);
  since_compaction_ = 0;
}

DenseCloud DenseMapper::Assemble() {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::vector<SE3> poses = AnchorPoses();
  coarse_.Rekey(poses);
  fine_.Rekey(poses);
  since_compaction_ = 0;
  std::set<int> moving;
  if (options_.remove_dynamic) {
    std::lock_guard<std::mutex> moving_lock(moving_mutex_);
    moving = moving_tracks_;
  }
  DenseCloud cloud = RemoveIsolatedPoints(coarse_.World(poses, moving), options_.leaf_size,
                                          options_.min_neighbours);
  const DenseCloud objects = fine_.World(poses, moving);
  cloud.insert(cloud.end(), objects.begin(), objects.end());
  stats_.exported_points = cloud.size();
  return cloud;
}

DenseMapStats DenseMapper::Stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  DenseMapStats stats = stats_;
  stats.frames = frames_.load();
  stats.background_points = coarse_.Size();
  stats.object_points = fine_.Size();
  stats.points = stats.background_points + stats.object_points;
  stats.memory_megabytes = static_cast<double>(coarse_.Bytes() + fine_.Bytes()) / (1024.0 * 1024.0);
  stats.keyframe_ms = Summarize(keyframe_ms_);
  return stats;
}

}  // namespace drvslam
