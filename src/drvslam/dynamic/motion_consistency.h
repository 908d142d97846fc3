// MotionConsistency: step 1 of the paper's dynamic-object handling. The previous frame's
// features are followed into the current image by pyramidal Lucas-Kanade flow; pairs on
// potentially-moving objects or near the border are set aside, the static scene's two-view
// geometry (a fundamental matrix, by RANSAC) is fitted to the rest, and every pair whose current
// point lies too far from its epipolar line is a moving point. When the camera barely
// translates (or sees one plane) the fundamental matrix is ill-posed: its epipole is free to
// line up with whatever moves. Then almost no static pair shows parallax (fits the fundamental
// matrix but not the best homography), and the homography's transfer error is tested instead.
// Beyond the paper, for RGB-D: the previous frame's depth turns each static pair into a 3-D to
// 2-D correspondence; the frame-to-frame camera motion is fitted to them (PnP in RANSAC) and
// every track's reprojection error tests it in both image directions, whatever the baseline
// (the epipolar test is blind along epipolar lines and ill-posed without translation).
// When enough tracks start on features the previous frame's tracking matched to map points as
// inliers (FlowTrack::anchored), the pose is fitted to those alone: in a crowd, movers may be
// most of the tracks, and a fit to all of them can follow the crowd (docs/dynamic-handling.md).
// The models are fitted on undistorted positions (lens distortion bends epipolar lines).
// Deterministic: OpenCV's RANSAC starts from a fixed random state.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/dynamic/dynamic_options.h"

namespace drvslam {

// One image's flow pyramid (of the image scaled by Dynamic.flowScale); built once per frame and
// reused as the previous one a frame later.
struct FlowImage {
  std::vector<cv::Mat> pyramid;
  cv::Size size;       // of the full-resolution image
  double scale = 1.0;  // pyramid level 0 = image scaled by this
  bool Empty() const { return pyramid.empty(); }
};

// gray: CV_8UC1. Throws drvslam::Error on another type or an empty image.
FlowImage BuildFlowImage(const cv::Mat& gray, const DynamicOptions& options);

enum class MotionModel { kNone, kFundamental, kHomography };
const char* MotionModelName(MotionModel model);

struct FlowTrack {
  int feature = -1;  // the caller's id of the tracked point (its previous-frame feature index)
  cv::Point2f prev;
  cv::Point2f cur;
  bool model_pair = false;  // used to fit the scene model
  // The previous feature was a map-point inlier of the previous frame's tracked pose: the
  // local map's static consensus, not this frame's tracks, vouches for it (set by the caller).
  bool anchored = false;
  // Epipolar distance (or homography transfer error), undistorted pixels.
  double residual = 0.0;
  bool moving = false;  // residual above the threshold of the model used
  // Reprojection error with the frame-to-frame pose (pixels); -1 where it is unknown (no pose,
  // no depth, or a depth edge at the previous point).
  double reprojection = -1.0;
  bool reprojection_moving = false;
  // The reprojection test where it is known, else the epipolar one.
  bool MovingBest() const { return reprojection >= 0.0 ? reprojection_moving : moving; }
};

struct MotionConsistencyResult {
  std::vector<FlowTrack> tracks;  // successfully tracked pairs only, in input order
  MotionModel model = MotionModel::kNone;
  cv::Matx33d fundamental = cv::Matx33d::zeros();
  cv::Matx33d homography = cv::Matx33d::zeros();
  int model_pairs = 0;     // pairs offered to RANSAC
  int model_inliers = 0;   // inliers of the model used
  int parallax_pairs = 0;  // model pairs fitting the fundamental matrix but not the homography
  int moving_points = 0;   // tracks flagged moving
  double median_flow = 0;  // over model pairs, pixels
  bool pose_ok = false;    // the frame-to-frame pose was fitted (needs depth)
  int pose_pairs = 0;      // model pairs with depth offered to the pose's RANSAC
  int pose_inliers = 0;
  // The pose was fitted to anchored model pairs only (enough of them had depth): the ego-motion
  // comes from what the map tracked as static, not from the tracks being judged.
  bool pose_anchored = false;
  int reprojection_moving = 0;  // tracks flagged by the reprojection test
};

class MotionConsistency {
 public:
  // Calls options.Check().
  explicit MotionConsistency(const DynamicOptions& options);

  // prev_points (with caller ids `ids`, same length) are tracked from `prev` to `cur` (same
  // size). prev_exclusion / cur_exclusion: empty or CV_8UC1 of the image size; pairs whose
  // previous / current point lies on a nonzero pixel do not fit the model (they are still
  // tested). `camera` (may be null: no distortion assumed) undistorts the positions the scene
  // models are fitted and tested on; with prev_depth (CV_32FC1 metres of the previous image, may
  // be empty) it enables the reprojection test. Tracks keep their distorted image positions.
  // Throws drvslam::Error when the sizes or lengths disagree.
  MotionConsistencyResult Run(const FlowImage& prev, const FlowImage& cur,
                              const std::vector<cv::Point2f>& prev_points,
                              const std::vector<int>& ids, const cv::Mat& prev_exclusion,
                              const cv::Mat& cur_exclusion, const cv::Mat& prev_depth = cv::Mat(),
                              const PinholeCamera* camera = nullptr) const;

  // Run's two halves, for callers that need the tracks before they know the current
  // exclusion mask (masks carried by these very tracks). Track: the Lucas-Kanade part (same
  // arguments as Run); the successful pairs, their tests not yet run. Test: the rest of Run on
  // those tracks, for images of `size`. Run(...) == Test(Track(...), ...).
  std::vector<FlowTrack> Track(const FlowImage& prev, const FlowImage& cur,
                               const std::vector<cv::Point2f>& prev_points,
                               const std::vector<int>& ids) const;
  MotionConsistencyResult Test(std::vector<FlowTrack> tracks, const cv::Size& size,
                               const cv::Mat& prev_exclusion, const cv::Mat& cur_exclusion,
                               const cv::Mat& prev_depth = cv::Mat(),
                               const PinholeCamera* camera = nullptr) const;

  // Distance of `cur` from the epipolar line F * prev in the current image.
  static double EpipolarDistance(const cv::Matx33d& fundamental, const cv::Point2f& prev,
                                 const cv::Point2f& cur);
  // |cur - H * prev|.
  static double TransferError(const cv::Matx33d& homography, const cv::Point2f& prev,
                              const cv::Point2f& cur);

 private:
  // Fits the frame-to-frame pose and fills each track's reprojection error. prev_pixels /
  // cur_pixels: the tracks' undistorted positions (depth is looked up at the distorted ones,
  // where the registered depth image has it).
  void TestReprojection(const cv::Mat& prev_depth, const PinholeCamera& camera,
                        const std::vector<cv::Point2f>& prev_pixels,
                        const std::vector<cv::Point2f>& cur_pixels,
                        MotionConsistencyResult* result) const;

  DynamicOptions options_;
};

}  // namespace drvslam
