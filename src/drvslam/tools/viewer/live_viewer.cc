#include "drvslam/tools/viewer/live_viewer.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/thread_name.h"
#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dynamic/dynamic_drawing.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/loop/loop_closer.h"
#include "drvslam/map/frame_features.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map.h"
#include "drvslam/map/map_point.h"
#include "drvslam/tools/viewer/viewer_assets.h"
#include "drvslam/tools/viewer/viewer_json.h"
#include "drvslam/tools/viewer/viewer_page.h"
#include "drvslam/tracking/tracking_state.h"

namespace drvslam {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A voxel's key: 21 bits per axis (+-10 km at 1 cm).
long long VoxelKey(const Eigen::Vector3f& p, double voxel) {
  const auto cell = [voxel](float v) {
    return static_cast<long long>(std::floor(v / voxel)) & ((1LL << 21) - 1);
  };
  return (cell(p.x()) << 42) | (cell(p.y()) << 21) | cell(p.z());
}

}  // namespace

struct LiveViewer::FrameSnapshot {
  long frame_id = -1;
  double timestamp = 0.0;
  TrackingState state = TrackingState::kNotInitialized;
  LocalizationQuality quality = LocalizationQuality::kLost;
  int inliers = 0;
  cv::Mat bgr;  // cloned
  // With the dynamic stage: its decisions (masks shared, never written after the frame).
  bool dynamic = false;
  std::vector<Instance> instances;
  std::vector<ObjectEvidence> objects;
  std::vector<MovingRegion> unlabelled;
  std::vector<cv::KeyPoint> kept;
  std::vector<cv::KeyPoint> removed;
  std::map<std::string, double> stage_ms;
  double frame_ms = 0.0;
  std::size_t frames = 0;
  std::size_t tracked = 0;
};

struct LiveViewer::Pending {
  std::vector<StampedPose> poses;  // every tracked pose since the viewer thread last looked
  std::optional<FrameSnapshot> latest;
  std::size_t arrivals = 0;  // frames since it last looked
};

LiveViewer::LiveViewer(System& system, LiveViewerOptions options)
    : system_(system),
      options_(std::move(options)),
      ground_truth_(options_.ground_truth.empty()
                        ? std::nullopt
                        : std::optional<Trajectory>(ReadTumTrajectory(options_.ground_truth))),
      server_(options_.port,
              [](const std::string& path) -> std::optional<HttpResponse> {
                if (path == "/" || path == "/index.html") {
                  return HttpResponse{200, "text/html; charset=utf-8", ServedViewerPage()};
                }
                if (path == "/viewer.js") {
                  return HttpResponse{200, "text/javascript; charset=utf-8",
                                      std::string(ViewerScript())};
                }
                if (path == "/data/run.json") {
                  return HttpResponse{200, "application/json", R"({"mode":"live"})"};
                }
                return std::nullopt;
              }),
      pending_(std::make_unique<Pending>()) {
  server_.Append(nlohmann::json({{"type", "hello"}, {"title", options_.title}}).dump());
  thread_ = std::thread([this] {
    NameCurrentThread("drv-viewer");
    Run();
  });
}

LiveViewer::~LiveViewer() { Finish(); }

std::string LiveViewer::Url() const { return "http://127.0.0.1:" + std::to_string(Port()) + "/"; }

void LiveViewer::OnFrame(const FrameObservation& o) {
  FrameSnapshot frame;
  frame.frame_id = o.track->frame_id;
  frame.timestamp = o.track->timestamp;
  frame.state = o.track->state;
  frame.quality = o.track->quality;
  frame.inliers = o.track->inliers;
  {
    // A recycled buffer: allocating (and page-faulting) a fresh image per frame on the tracking
    // thread showed up as stalls of tens of ms on a loaded machine.
    std::lock_guard<std::mutex> lock(mutex_);
    if (!spare_images_.empty()) {
      frame.bgr = std::move(spare_images_.back());
      spare_images_.pop_back();
    }
  }
  o.bgr->copyTo(frame.bgr);
  if (o.dynamic) {
    frame.dynamic = true;
    frame.instances = o.dynamic->instances;
    frame.objects = o.dynamic->objects;
    frame.unlabelled = o.dynamic->unlabelled;
    frame.kept = o.dynamic->kept_features;
    frame.removed = o.dynamic->removed_features;
  } else if (o.features) {
    frame.kept = o.features->Keypoints();
  }
  frame.stage_ms = o.stage_ms;
  frame.frame_ms = o.frame_ms;
  frame.frames = o.frames;
  frame.tracked = o.tracked;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (o.track->pose_valid) pending_->poses.push_back({o.track->timestamp, o.track->T_wc});
    // Replaces a frame the viewer thread did not take; its image goes back to the spares.
    if (pending_->latest) RecycleImage(std::move(pending_->latest->bgr));
    pending_->latest = std::move(frame);
    ++pending_->arrivals;
  }
  wake_.notify_one();
}

void LiveViewer::Run() {
  const Clock::time_point start = Clock::now();
  double next_image = 0.0, next_map = 0.0, next_dense = 0.0;
  while (true) {
    Pending taken;
    bool finishing = false;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait_for(lock, std::chrono::milliseconds(100),
                     [this] { return finishing_ || pending_->latest.has_value(); });
      std::swap(taken, *pending_);
      finishing = finishing_;
    }
    const double now = SecondsSince(start);
    try {
      Publish(taken, finishing, now, &next_image, &next_map, &next_dense);
    } catch (const std::exception& error) {
      // The viewer must never take the run down: the page misses this update.
      spdlog::warn("viewer: update failed: {}", error.what());
    }
    if (finishing) break;
  }
  server_.Append(nlohmann::json({{"type", "end"}}).dump());
}

void LiveViewer::Publish(Pending& taken, bool finishing, double now, double* next_image,
                         double* next_map, double* next_dense) {
  for (std::size_t k = 0; k < taken.arrivals; ++k) arrival_s_.push_back(now);
  while (!arrival_s_.empty() && arrival_s_.front() < now - 1.0) arrival_s_.pop_front();
  if (taken.latest) {
    PublishFrame(*taken.latest, std::move(taken.poses));
    if (now >= *next_image) {
      PublishImage(*taken.latest);
      *next_image = now + options_.image_interval_s;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    RecycleImage(std::move(taken.latest->bgr));
  }
  if (finishing || now >= *next_map) {
    PublishMap();
    PublishLoops();
    PublishTruth();
    *next_map = now + options_.map_interval_s;
  }
  if (finishing || now >= *next_dense) {
    PublishDense();
    *next_dense = now + options_.dense_interval_s;
  }
}

void LiveViewer::RecycleImage(cv::Mat image) {
  // Only a buffer nobody else holds can be written again; two cover the frame in flight.
  if (image.u && image.u->refcount == 1 && spare_images_.size() < 2) {
    spare_images_.push_back(std::move(image));
  }
}

void LiveViewer::PublishFrame(const FrameSnapshot& frame, std::vector<StampedPose> poses) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, ms] : frame.stage_ms) stages[name] = ms;
  nlohmann::json batch = nlohmann::json::array();
  for (const StampedPose& pose : poses) {
    batch.push_back(PoseJson(pose));
    trajectory_.push_back(pose);
  }
  const nlohmann::json message = {{"type", "frame"},
                                  {"frame_id", frame.frame_id},
                                  {"timestamp", frame.timestamp},
                                  {"state", TrackingStateName(frame.state)},
                                  {"quality", LocalizationQualityName(frame.quality)},
                                  {"poses", batch},
                                  {"fps", static_cast<double>(arrival_s_.size())},
                                  {"frame_ms", frame.frame_ms},
                                  {"stages", stages},
                                  {"inliers", frame.inliers},
                                  {"kept", frame.kept.size()},
                                  {"removed", frame.removed.size()},
                                  {"frames", frame.frames},
                                  {"tracked", frame.tracked}};
  // In the log, not latest-only: a page that reads slowly still gets every pose, later.
  server_.Append(message.dump());
}

void LiveViewer::PublishImage(const FrameSnapshot& frame) {
  cv::Mat picture;
  if (frame.dynamic) {
    picture = DrawDynamicFrame(frame.bgr, frame.instances, frame.objects, frame.unlabelled,
                               frame.kept, frame.removed);
  } else {
    picture = frame.bgr.channels() == 1 ? cv::Mat() : frame.bgr.clone();
    if (frame.bgr.channels() == 1) cv::cvtColor(frame.bgr, picture, cv::COLOR_GRAY2BGR);
    for (const cv::KeyPoint& k : frame.kept)
      cv::circle(picture, k.pt, 2, cv::Scalar(0, 200, 0), -1);
  }
  std::vector<unsigned char> jpeg;
  cv::imencode(".jpg", picture, jpeg, {cv::IMWRITE_JPEG_QUALITY, options_.jpeg_quality});
  const nlohmann::json message = {{"type", "image"},
                                  {"frame_id", frame.frame_id},
                                  {"width", picture.cols},
                                  {"height", picture.rows},
                                  {"jpeg", Base64(jpeg.data(), jpeg.size())}};
  server_.Replace("image", message.dump());
}

void LiveViewer::PublishMap() {
  DenseCloud points;
  for (const std::shared_ptr<MapPoint>& point : system_.GetMap().MapPoints()) {
    if (point->IsBad()) continue;
    DensePoint p;
    p.position = point->Position().cast<float>();
    points.push_back(p);
  }
  Trajectory keyframes;
  for (const std::shared_ptr<KeyFrame>& keyframe : system_.GetMap().KeyFrames()) {
    if (keyframe->IsBad()) continue;
    keyframes.push_back({keyframe->Timestamp(), keyframe->InversePose()});
  }
  const nlohmann::json message = {{"type", "map"},
                                  {"sparse", CloudJson(points, points.size(), false)},
                                  {"keyframes", TrajectoryJson(keyframes)}};
  server_.Replace("map", message.dump());
}

void LiveViewer::PublishLoops() {
  const std::vector<LoopEvent> loops = system_.LoopClosures();
  if (loops.size() == loops_seen_) return;
  loops_seen_ = loops.size();
  nlohmann::json list = nlohmann::json::array();
  for (const LoopEvent& loop : loops) {
    list.push_back({{"keyframe", loop.keyframe_id},
                    {"loop_keyframe", loop.loop_keyframe_id},
                    {"timestamp", loop.timestamp},
                    {"matches", loop.matches},
                    {"correction_m", loop.correction_m},
                    {"correction_deg", loop.correction_deg}});
  }
  server_.Replace("loops", nlohmann::json({{"type", "loops"}, {"loops", list}}).dump());
  // The correction moved the dense points already sent: they are sent again where they are now.
  dense_voxels_sent_.clear();
  dense_sent_ = 0;
  dense_keyframes_seen_ = 0;
}

void LiveViewer::PublishDense() {
  DenseMapper* dense = system_.Dense();
  if (!dense) return;
  const std::size_t keyframes = dense->Stats().keyframes;
  if (keyframes == dense_keyframes_seen_) return;
  const bool reset = dense_keyframes_seen_ == 0 && dense_sent_ == 0;
  dense_keyframes_seen_ = keyframes;
  // Assemble gives the map with the current keyframe poses (what ExportDenseMap writes).
  const DenseCloud cloud = dense->Assemble();
  DenseCloud chunk;
  for (const DensePoint& p : cloud) {
    if (dense_sent_ + chunk.size() >= options_.dense_budget) break;
    if (dense_voxels_sent_.insert(VoxelKey(p.position, options_.dense_voxel_m)).second) {
      chunk.push_back(p);
    }
  }
  dense_sent_ += chunk.size();
  const nlohmann::json message = {{"type", "dense"},
                                  {"reset", reset},
                                  {"chunk", CloudJson(chunk, chunk.size(), true)},
                                  {"total", cloud.size()}};
  server_.Append(message.dump());
}

void LiveViewer::PublishTruth() {
  if (!ground_truth_ || trajectory_.size() < 3) return;
  std::string why;
  const std::optional<TruthOverlay> overlay = OverlayTruth(*ground_truth_, trajectory_, &why);
  if (!overlay) return;
  const nlohmann::json message = {
      {"type", "truth"},
      {"ground_truth", overlay->ground_truth},
      {"errors", overlay->errors},
      {"ate", {{"rmse", overlay->rmse}, {"matched", overlay->matched}}}};
  server_.Replace("truth", message.dump());
}

void LiveViewer::Finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
    finishing_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  server_.Flush(1000);
  server_.Stop();
}

}  // namespace drvslam
