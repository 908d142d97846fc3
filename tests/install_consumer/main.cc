// Tracks three frames of a still camera facing a textured wall 2 m away, with raw 16-bit
// depth as a sensor gives it, through the installed library, and prints what TrackRGBD
// returns. Exit status 0 when every frame was tracked. Usage: drvslam_consumer SETTINGS
#include <drvslam/core/error.h>
#include <drvslam/core/settings.h>
#include <drvslam/core/settings_file.h>
#include <drvslam/system.h>
#include <drvslam/system_options.h>
#include <drvslam/system_stats.h>
#include <drvslam/tracking/tracker_options.h>

#include <cstdio>
#include <opencv2/core.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SETTINGS\n", argv[0]);
    return 2;
  }
  try {
    const drvslam::SettingsFile file(argv[1]);
    const drvslam::Settings settings = drvslam::LoadSettings(file);
    drvslam::SystemOptions options;
    options.sequential = true;
    options.relocalization.vocabulary = DRVSLAM_CONSUMER_VOCABULARY;
    drvslam::System slam(settings, drvslam::LoadTrackerOptions(file), options);

    cv::Mat bgr(settings.camera.height, settings.camera.width, CV_8UC3);
    cv::RNG rng(7);
    rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
    const cv::Mat depth(bgr.size(), CV_16UC1, cv::Scalar(2.0 * settings.depth.depth_map_factor));
    for (int i = 0; i < 3; ++i) {
      const drvslam::TrackResult result = slam.TrackRGBD(bgr, depth, i / settings.camera.fps);
      const Eigen::Vector3d& t = result.T_wc.Translation();
      std::printf("frame %ld: %s, pose_valid %d, t_wc %.4f %.4f %.4f, inliers %d\n",
                  result.frame_id, drvslam::TrackingStateName(result.state), result.pose_valid,
                  t.x(), t.y(), t.z(), result.inliers);
    }
    slam.Shutdown();
    const drvslam::SystemStats stats = slam.Stats();
    std::printf("tracked %zu of %zu frames; %zu keyframes, %zu map points; vocabulary %s\n",
                stats.tracked, stats.frames, stats.keyframes, stats.map_points,
                slam.Vocabulary() ? "loaded" : "none");
    return stats.tracked == 3 ? 0 : 1;
  } catch (const drvslam::Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 2;
  }
}
