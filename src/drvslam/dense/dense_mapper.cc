#include "drvslam/dense/dense_mapper.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "drvslam/core/thread_budget.h"
#include "drvslam/core/thread_name.h"
#include "drvslam/dense/dense_surface.h"
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
                         bool sequential, StageTimings* timings, bool never_block)
    : camera_(camera),
      options_(Checked(options)),
      sequential_(sequential),
      timings_(timings),
      never_block_(never_block),
      rays_(MakePixelRays(camera)),
      frames_before_(options.enhancement_frames / 2),
      frames_after_(options.enhancement_frames - options.enhancement_frames / 2),
      coarse_(options.leaf_size, {options.min_views, options.evidence_max, options.min_view_span}),
      fine_(options.object_leaf_size, {1, options.evidence_max, 0.0}),
      queue_(static_cast<std::size_t>(never_block ? options.live_queue_capacity
                                                  : options.queue_capacity)) {
  if (!sequential_) worker_ = std::thread([this] { Run(); });
}

DenseMapper::~DenseMapper() { Shutdown(); }

void DenseMapper::Shutdown() {
  if (stopped_) return;
  DispatchWaiting(/*flush=*/true);
  stopped_ = true;
  queue_.Close();
  {
    // What is left no longer competes with tracking: drain it at the process's priority (a
    // stage at nice 19 next to a busy machine would take many seconds per keyframe).
    std::lock_guard<std::mutex> lock(worker_priority_mutex_);
    RestoreThreadPriority(worker_priority_);
  }
  if (worker_.joinable()) worker_.join();
}

void DenseMapper::Run() {
  NameCurrentThread("drv-dense");
  {
    std::lock_guard<std::mutex> lock(worker_priority_mutex_);
    worker_priority_ = LowerCurrentThreadPriority(BackgroundStage::kDenseMapping);
  }
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

void DenseMapper::Remember(DenseFrame frame) {
  if (options_.enhancement_frames == 0) return;
  // Later frames join the keyframes that wait for them; the ring keeps the latest for the next.
  for (KeyFrameJob& job : waiting_) {
    if (job.frames_to_wait == 0) continue;
    job.neighbours.push_back(frame);
    --job.frames_to_wait;
  }
  if (frames_before_ > 0) {
    ring_.push_back(std::move(frame));
    if (ring_.size() > static_cast<std::size_t>(frames_before_)) ring_.erase(ring_.begin());
  }
}

void DenseMapper::AddFrame(DenseFrame frame) {
  CheckDenseFrame(frame);
  MarkMoving(&frame);
  ++frames_;
  Remember(std::move(frame));
  DispatchWaiting(/*flush=*/false);
}

void DenseMapper::AddKeyFrame(DenseFrame frame, std::shared_ptr<const KeyFrame> keyframe) {
  CheckDenseFrame(frame);
  MarkMoving(&frame);
  ++frames_;
  KeyFrameJob job;
  // The ring holds exactly the latest frames_before_ frames and the job then collects the next
  // frames_after_: the nearest ones in time, the same whether the job runs at once or later.
  job.neighbours = ring_;
  job.keyframe = std::move(keyframe);
  job.frame = frame;
  job.frames_to_wait = frames_after_;
  Remember(std::move(frame));
  waiting_.push_back(std::move(job));
  // After shutdown no later frames are expected: integrate at once.
  DispatchWaiting(/*flush=*/stopped_);
}

void DenseMapper::DispatchWaiting(bool flush) {
  // In order: a keyframe never overtakes an earlier one.
  std::size_t done = 0;
  while (done < waiting_.size() && (flush || waiting_[done].frames_to_wait == 0)) {
    Dispatch(std::move(waiting_[done]));
    ++done;
  }
  waiting_.erase(waiting_.begin(), waiting_.begin() + static_cast<std::ptrdiff_t>(done));
}

void DenseMapper::Dispatch(Job job) {
  if (sequential_ || stopped_) {
    Process(std::move(job));
  } else if (never_block_ && std::holds_alternative<KeyFrameJob>(job)) {
    if (!queue_.TryPush(std::move(job))) ++keyframes_dropped_;
  } else {
    queue_.Push(std::move(job));
  }
}

void DenseMapper::Reset() {
  // Waiting keyframes belong to the map being dropped.
  waiting_.clear();
  ring_.clear();
  Dispatch(ResetJob{});
}

namespace {

// Points of the anchor's camera frame, one per voxel of the world grid (through T_wa): the
// map's own voxels, so a view counts once per voxel, with the summed weight of its pixels.
SurfaceSamples DownsampleOnWorldGrid(SurfaceSamples local, const SE3& T_wa, double leaf) {
  const Eigen::Matrix3f R = T_wa.Rotation().cast<float>();
  const Eigen::Vector3f t = T_wa.Translation().cast<float>();
  for (DensePoint& p : local.points) p.position = R * p.position + t;
  SurfaceSamples voxels;
  voxels.points = WeightedVoxelDownsample(local.points, local.weights, leaf, &voxels.weights);
  const Eigen::Matrix3f Rt = R.transpose();
  for (DensePoint& p : voxels.points) p.position = Rt * (p.position - t);
  return voxels;
}

// Key-object points weighted by their depth noise alone (enhancement frames see them from
// about the keyframe's place; their normals would cost more than they change).
void AppendWithDepthWeights(const DenseCloud& points, SurfaceSamples* samples) {
  for (const DensePoint& p : points) {
    samples->points.push_back(p);
    samples->weights.push_back(DepthNoiseWeight(p.position.z()));
  }
}

// A neighbouring frame's verdict on the keyframe's points: its left-out objects and depth.
struct NeighbourMasks {
  const cv::Mat* moving;
  const cv::Mat* depth;
  Eigen::Matrix3f R_nk;
  Eigen::Vector3f t_nk;
};

// Drops the points (keyframe frame) that a neighbour sees, at the point's depth within the
// carving margin, on a left-out object.
SurfaceSamples DropPointsSeenMoving(SurfaceSamples samples,
                                    const std::vector<NeighbourMasks>& views,
                                    const CameraOptions& camera, const DenseMapOptions& options) {
  if (views.empty()) return samples;
  SurfaceSamples kept;
  kept.points.reserve(samples.points.size());
  kept.weights.reserve(samples.points.size());
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    const DensePoint& p = samples.points[i];
    bool moving = false;
    for (const NeighbourMasks& view : views) {
      const Eigen::Vector3f c = view.R_nk * p.position + view.t_nk;
      if (c.z() <= 0.1f) continue;
      const Eigen::Vector2f pixel = ProjectToImage(camera, c);
      const int x = static_cast<int>(std::lround(pixel.x()));
      const int y = static_cast<int>(std::lround(pixel.y()));
      if (x < 0 || y < 0 || x >= view.moving->cols || y >= view.moving->rows) continue;
      if (!view.moving->at<uint8_t>(y, x)) continue;
      const float z = view.depth->at<float>(y, x);
      const float margin =
          static_cast<float>(options.carve_margin + options.carve_margin_quadratic * c.z() * c.z());
      if (std::isfinite(z) && std::abs(z - c.z()) <= margin) {
        moving = true;
        break;
      }
    }
    if (moving) continue;
    kept.points.push_back(p);
    kept.weights.push_back(samples.weights[i]);
  }
  return kept;
}

}  // namespace

void DenseMapper::Integrate(KeyFrameJob job) {
  const Stopwatch watch;
  const DenseFrame& frame = job.frame;
  const PixelRoles roles = PaintRoles(frame, options_);
  const std::size_t mapped_pixels = CountMappedPixels(frame, roles, options_);
  const SE3 T_wa = job.keyframe ? CurrentKeyFramePose(*job.keyframe) : frame.T_wc;

  // Key objects of the keyframe and its neighbours, in the keyframe's camera frame.
  SurfaceSamples objects;
  AppendWithDepthWeights(BackProject(frame, roles, PixelRole::kKeyObject, rays_, options_),
                         &objects);
  std::size_t used = 0;
  const SE3 T_kw = frame.T_wc.Inverse();
  std::vector<PixelRoles> all_neighbour_roles;
  all_neighbour_roles.reserve(job.neighbours.size());
  std::vector<NeighbourMasks> vetoes;
  for (const DenseFrame& neighbour : job.neighbours) {
    all_neighbour_roles.push_back(PaintRoles(neighbour, options_));
    const PixelRoles& neighbour_roles = all_neighbour_roles.back();
    if (options_.neighbour_veto && !neighbour_roles.moving.empty()) {
      const SE3 T_nk = neighbour.T_wc.Inverse() * frame.T_wc;
      vetoes.push_back({&neighbour_roles.moving, &neighbour.depth, T_nk.Rotation().cast<float>(),
                        T_nk.Translation().cast<float>()});
    }
    DenseCloud points =
        BackProject(neighbour, neighbour_roles, PixelRole::kKeyObject, rays_, options_);
    if (points.empty()) continue;
    ++used;
    const SE3 T_kn = T_kw * neighbour.T_wc;
    const Eigen::Matrix3f R = T_kn.Rotation().cast<float>();
    const Eigen::Vector3f t = T_kn.Translation().cast<float>();
    const std::size_t first = objects.points.size();
    AppendWithDepthWeights(points, &objects);  // the neighbour's own depth noise
    for (std::size_t i = first; i < objects.points.size(); ++i) {
      objects.points[i].position = R * objects.points[i].position + t;
    }
  }
  const SurfaceSamples fine =
      DownsampleOnWorldGrid(std::move(objects), T_wa, options_.object_leaf_size);
  const SurfaceSamples coarse =
      DropPointsSeenMoving(DownsampleOnWorldGrid(BackProjectSurfaces(frame, roles, rays_, options_),
                                                 T_wa, options_.leaf_size),
                           vetoes, camera_, options_);

  std::lock_guard<std::mutex> lock(mutex_);
  ReleaseCulledLocked();
  std::vector<SE3> poses = AnchorPoses();
  if (options_.carve) {
    // The keyframe's depth votes before its own points go in: what it sees through is free.
    CarvingView view;
    view.depth = &frame.depth;
    view.camera = &camera_;
    view.T_cw = T_wa.Inverse();
    view.margin = options_.carve_margin;
    view.quadratic = options_.carve_margin_quadratic;
    stats_.carving_votes += coarse_.Carve(view, poses) + fine_.Carve(view, poses);
  }
  const int anchor = static_cast<int>(anchors_.size());
  anchors_.push_back({job.keyframe, SE3::Identity(), frame.T_wc, frame.timestamp});
  poses.push_back(T_wa);
  coarse_.Insert(coarse.points, coarse.weights, anchor, poses);
  fine_.Insert(fine.points, fine.weights, anchor, poses);
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
    poses.push_back(anchor.keyframe ? CurrentKeyFramePose(*anchor.keyframe) * anchor.T_ka
                                    : anchor.T_wc);
  }
  return poses;
}

void DenseMapper::ReleaseCulledLocked() {
  for (Anchor& anchor : anchors_) {
    while (anchor.keyframe && anchor.keyframe->IsBad()) {
      std::shared_ptr<const KeyFrame> parent = anchor.keyframe->Parent();
      if (!parent) break;  // the origin is never culled; a parentless one keeps its last pose
      // T_wk = T_wp * T_kp^-1, so the anchor relative to the parent is T_kp^-1 * T_ka.
      anchor.T_ka = anchor.keyframe->PoseRelativeToParent().Inverse() * anchor.T_ka;
      anchor.keyframe = std::move(parent);
    }
  }
}

std::vector<double> DenseMapper::AnchorTimes() const {
  std::vector<double> times;
  times.reserve(anchors_.size());
  for (const Anchor& anchor : anchors_) times.push_back(anchor.timestamp);
  return times;
}

void DenseMapper::CompactLocked() {
  const std::vector<SE3> poses = AnchorPoses();
  coarse_.Rekey(poses);
  fine_.Rekey(poses);
  since_compaction_ = 0;
}

DenseCloud DenseMapper::Assemble() { return AssembleRays().cloud; }

DenseMapRays DenseMapper::AssembleRays() {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::vector<SE3> poses = AnchorPoses();
  const std::vector<double> times = AnchorTimes();
  coarse_.Rekey(poses);
  fine_.Rekey(poses);
  since_compaction_ = 0;
  std::set<int> moving;
  if (options_.remove_dynamic) {
    std::lock_guard<std::mutex> moving_lock(moving_mutex_);
    moving = moving_tracks_;
  }
  DenseMapRays rays;
  std::vector<int> coarse_anchors;
  const DenseCloud coarse = coarse_.World(poses, times, moving, &coarse_anchors);
  const std::vector<std::size_t> kept =
      ConnectedPointIndices(coarse, options_.leaf_size, options_.min_neighbours);
  std::vector<int> object_anchors;
  const DenseCloud objects = fine_.World(poses, times, moving, &object_anchors);
  rays.cloud.reserve(kept.size() + objects.size());
  rays.origin_of_point.reserve(kept.size() + objects.size());
  for (const std::size_t i : kept) {
    rays.cloud.push_back(coarse[i]);
    rays.origin_of_point.push_back(coarse_anchors[i]);
  }
  rays.cloud.insert(rays.cloud.end(), objects.begin(), objects.end());
  rays.origin_of_point.insert(rays.origin_of_point.end(), object_anchors.begin(),
                              object_anchors.end());
  rays.origins.reserve(poses.size());
  rays.downs.reserve(poses.size());
  for (const SE3& T_wa : poses) {
    rays.origins.push_back(T_wa.Translation().cast<float>());
    rays.downs.push_back(T_wa.Rotation().col(1).cast<float>());
  }
  stats_.exported_points = rays.cloud.size();
  return rays;
}

DenseMapStats DenseMapper::Stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  DenseMapStats stats = stats_;
  stats.frames = frames_.load();
  stats.keyframes_dropped = keyframes_dropped_.load();
  stats.background_points = coarse_.Size();
  stats.object_points = fine_.Size();
  stats.points = stats.background_points + stats.object_points;
  stats.memory_megabytes = static_cast<double>(coarse_.Bytes() + fine_.Bytes()) / (1024.0 * 1024.0);
  stats.keyframe_ms = Summarize(keyframe_ms_);
  return stats;
}

DenseMapSnapshot DenseMapper::Snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::set<int> moving;
  if (options_.remove_dynamic) {
    std::lock_guard<std::mutex> moving_lock(moving_mutex_);
    moving = moving_tracks_;
  }
  const std::vector<SE3> poses = AnchorPoses();
  DenseMapSnapshot snapshot;
  // Per anchor: the live keyframe it is saved under and the move into that keyframe's frame.
  std::vector<SE3> to_saved_frame(anchors_.size());
  for (std::size_t a = 0; a < anchors_.size(); ++a) {
    DenseAnchorRecord record;
    record.T_wc = poses[a];
    record.timestamp = anchors_[a].timestamp;
    std::shared_ptr<const KeyFrame> keyframe = anchors_[a].keyframe;
    for (int step = 0; keyframe && keyframe->IsBad() && step < kMaxParentSteps; ++step) {
      keyframe = keyframe->Parent();
    }
    if (keyframe && !keyframe->IsBad()) {
      record.keyframe_id = keyframe->Id();
      record.T_wc = keyframe->InversePose();
      to_saved_frame[a] = record.T_wc.Inverse() * poses[a];
    }
    snapshot.anchors.push_back(record);
  }
  const auto convert = [&](const std::vector<DenseVoxelRecord>& records) {
    std::vector<DenseVoxelRecord> out;
    out.reserve(records.size());
    for (DenseVoxelRecord record : records) {
      if (record.point.track >= 0 && moving.count(record.point.track)) continue;
      record.point.track = -1;
      record.point.position =
          (to_saved_frame[record.anchor] * record.point.position.cast<double>()).cast<float>();
      out.push_back(record);
    }
    return out;
  };
  snapshot.coarse = convert(coarse_.Records());
  snapshot.fine = convert(fine_.Records());
  return snapshot;
}

void DenseMapper::Restore(const DenseMapSnapshot& snapshot,
                          const std::function<std::shared_ptr<const KeyFrame>(long)>& keyframe_of) {
  std::lock_guard<std::mutex> lock(mutex_);
  anchors_.clear();
  for (const DenseAnchorRecord& record : snapshot.anchors) {
    Anchor anchor;
    anchor.T_wc = record.T_wc;
    anchor.timestamp = record.timestamp;
    if (record.keyframe_id >= 0) anchor.keyframe = keyframe_of(record.keyframe_id);
    anchors_.push_back(std::move(anchor));
  }
  const std::vector<SE3> poses = AnchorPoses();
  coarse_.Restore(snapshot.coarse, poses);
  fine_.Restore(snapshot.fine, poses);
  since_compaction_ = 0;
}

}  // namespace drvslam
