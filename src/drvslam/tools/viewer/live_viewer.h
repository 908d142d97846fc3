// LiveViewer: `drvslam run --viewer [PORT]`. Serves the viewer page on 127.0.0.1 and keeps it
// up to date over a WebSocket while the run goes on: poses, keyframes, sparse map points, the
// dense map in chunks, the current image with instance masks (moving red, static green) and kept
// (green) and removed (red) features, tracking state, fps, per-stage times and loop closures.
//
// Threads: OnFrame runs on the tracking thread and only copies: the pose into a list, the image
// (copied into a recycled buffer) and the dynamic report (masks by reference count) into a
// latest-only slot, which the next frame overwrites when the viewer thread has not taken it yet.
// The viewer thread draws, encodes JPEG and JSON, reads the map, the dense map and the loop
// closures, and hands messages to WebServer, whose clients each have a bounded backlog: a slow or
// closed browser loses updates, and tracking never waits for it.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <unordered_set>
#include <vector>

#include "drvslam/frame_observer.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/system.h"
#include "drvslam/tools/viewer/web_server.h"

namespace drvslam {

struct LiveViewerOptions {
  int port = 8080;    // 0: any free port (LiveViewer::Port says which)
  std::string title;  // shown on the page
  // TUM ground truth to draw aligned to the trajectory (empty: none).
  std::string ground_truth;
  // Dense points the page receives at most; later chunks are left out and the page says so.
  std::size_t dense_budget = 400000;
  double dense_voxel_m = 0.01;  // a dense point is sent once per voxel of this size
  double map_interval_s = 1.0;  // sparse map, keyframes, loops, ground truth
  double dense_interval_s = 2.0;
  double image_interval_s = 0.1;  // at most 10 images a second
  int jpeg_quality = 70;
};

class LiveViewer : public FrameObserver {
 public:
  // Starts serving. Throws Error when the port is in use or the ground truth cannot be read.
  // `system` must outlive this object.
  LiveViewer(System& system, LiveViewerOptions options);
  ~LiveViewer() override;  // Finish
  LiveViewer(const LiveViewer&) = delete;
  LiveViewer& operator=(const LiveViewer&) = delete;

  int Port() const { return server_.Port(); }
  std::string Url() const;
  // What the page(s) have been sent so far; final once Finish has returned.
  WebTraffic Traffic() const { return server_.Traffic(); }

  void OnFrame(const FrameObservation& observation) override;

  // After the run: sends the final map and an "end" message, gives connected pages up to a
  // second to receive them, and stops serving. Idempotent.
  void Finish();

 private:
  // What the viewer thread takes from the tracking thread.
  struct FrameSnapshot;
  struct Pending;

  void Run();
  // Keeps a frame's image buffer for a later frame (caller holds mutex_).
  void RecycleImage(cv::Mat image);
  // One round of the viewer thread: what `taken` holds, and what is due at `now` (seconds).
  void Publish(Pending& taken, bool finishing, double now, double* next_image, double* next_map,
               double* next_dense);
  void PublishFrame(const FrameSnapshot& frame, std::vector<StampedPose> poses);
  void PublishImage(const FrameSnapshot& frame);
  void PublishMap();
  void PublishDense();
  void PublishLoops();
  void PublishTruth();

  System& system_;
  LiveViewerOptions options_;
  std::optional<Trajectory> ground_truth_;
  WebServer server_;

  std::mutex mutex_;  // guards pending_, spare_images_, finishing_ and finished_
  std::condition_variable wake_;
  std::unique_ptr<Pending> pending_;
  std::vector<cv::Mat> spare_images_;  // image buffers to copy the next frames into
  bool finishing_ = false;
  bool finished_ = false;
  std::thread thread_;

  // Viewer thread only.
  Trajectory trajectory_;
  std::deque<double> arrival_s_;  // wall-clock arrivals of the last second, for fps
  std::unordered_set<long long> dense_voxels_sent_;
  std::size_t dense_sent_ = 0;
  std::size_t dense_keyframes_seen_ = 0;
  std::size_t loops_seen_ = 0;
};

}  // namespace drvslam
