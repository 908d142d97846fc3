#include "drvslam/dynamic/motion_consistency.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "drvslam/core/enum_names.h"
#include "drvslam/core/error.h"
#include "drvslam/core/pixel_index.h"
#include "drvslam/semantic/mask_lookup.h"

namespace drvslam {
namespace {

bool NearBorder(const cv::Point2f& p, const cv::Size& size, int margin) {
  return p.x < margin || p.y < margin || p.x >= size.width - margin || p.y >= size.height - margin;
}

void CheckMask(const cv::Mat& mask, const cv::Size& size, const char* what) {
  if (mask.empty()) return;
  if (mask.type() != CV_8UC1 || mask.size() != size) {
    throw Error(std::string("MotionConsistency: ") + what +
                " must be empty or CV_8UC1 of the image size");
  }
}

}  // namespace

const char* MotionModelName(MotionModel model) {
  static constexpr EnumName<MotionModel> kNames[] = {{MotionModel::kNone, "none"},
                                                     {MotionModel::kFundamental, "fundamental"},
                                                     {MotionModel::kHomography, "homography"}};
  return NameOf(model, kNames, "?");
}

FlowImage BuildFlowImage(const cv::Mat& gray, const DynamicOptions& options) {
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw Error("BuildFlowImage: expected a non-empty CV_8UC1 image");
  }
  FlowImage image;
  image.size = gray.size();
  image.scale = options.flow_scale;
  cv::Mat scaled = gray;
  if (options.flow_scale < 1.0) {
    cv::resize(gray, scaled, cv::Size(), options.flow_scale, options.flow_scale, cv::INTER_AREA);
  }
  cv::buildOpticalFlowPyramid(scaled, image.pyramid,
                              cv::Size(options.flow_window, options.flow_window),
                              options.flow_levels, true);
  return image;
}

MotionConsistency::MotionConsistency(const DynamicOptions& options) : options_(options) {
  options_.Check();
}

double MotionConsistency::EpipolarDistance(const cv::Matx33d& fundamental, const cv::Point2f& prev,
                                           const cv::Point2f& cur) {
  const cv::Vec3d line = fundamental * cv::Vec3d(prev.x, prev.y, 1.0);
  const double norm = std::hypot(line[0], line[1]);
  if (norm <= 0.0) return 0.0;
  return std::abs(line[0] * cur.x + line[1] * cur.y + line[2]) / norm;
}

double MotionConsistency::TransferError(const cv::Matx33d& homography, const cv::Point2f& prev,
                                        const cv::Point2f& cur) {
  const cv::Vec3d mapped = homography * cv::Vec3d(prev.x, prev.y, 1.0);
  if (std::abs(mapped[2]) < 1e-12) return 1e9;
  return std::hypot(mapped[0] / mapped[2] - cur.x, mapped[1] / mapped[2] - cur.y);
}

MotionConsistencyResult MotionConsistency::Run(
    const FlowImage& prev, const FlowImage& cur, const std::vector<cv::Point2f>& prev_points,
    const std::vector<int>& ids, const cv::Mat& prev_exclusion, const cv::Mat& cur_exclusion,
    const cv::Mat& prev_depth, const PinholeCamera* camera) const {
  return Test(Track(prev, cur, prev_points, ids), cur.size, prev_exclusion, cur_exclusion,
              prev_depth, camera);
}

std::vector<FlowTrack> MotionConsistency::Track(const FlowImage& prev, const FlowImage& cur,
                                                const std::vector<cv::Point2f>& prev_points,
                                                const std::vector<int>& ids) const {
  if (prev.Empty() || cur.Empty() || prev.size != cur.size || prev.scale != cur.scale) {
    throw Error("MotionConsistency: the two flow images must exist and have one size and scale");
  }
  if (ids.size() != prev_points.size()) {
    throw Error("MotionConsistency: one id per point is needed");
  }
  std::vector<FlowTrack> tracks;
  if (prev_points.empty()) return tracks;

  const cv::Size window(options_.flow_window, options_.flow_window);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 10, 0.03);
  const float scale = static_cast<float>(prev.scale);
  std::vector<cv::Point2f> scaled(prev_points.size());
  for (std::size_t i = 0; i < prev_points.size(); ++i) scaled[i] = prev_points[i] * scale;
  std::vector<cv::Point2f> next;
  std::vector<uchar> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(prev.pyramid, cur.pyramid, scaled, next, status, error, window,
                           options_.flow_levels, criteria);
  std::vector<uchar> back_status;
  std::vector<cv::Point2f> back;
  if (options_.flow_check > 0.0) {
    back = scaled;
    cv::calcOpticalFlowPyrLK(cur.pyramid, prev.pyramid, next, back, back_status, error, window,
                             options_.flow_levels, criteria, cv::OPTFLOW_USE_INITIAL_FLOW);
  }
  for (cv::Point2f& p : next) p *= 1.0f / scale;
  for (cv::Point2f& p : back) p *= 1.0f / scale;

  const cv::Rect inside(0, 0, cur.size.width, cur.size.height);
  for (std::size_t i = 0; i < prev_points.size(); ++i) {
    if (!status[i] || !inside.contains(cv::Point(cvFloor(next[i].x), cvFloor(next[i].y)))) {
      continue;
    }
    if (options_.flow_check > 0.0 &&
        (!back_status[i] || std::hypot(back[i].x - prev_points[i].x, back[i].y - prev_points[i].y) >
                                options_.flow_check)) {
      continue;
    }
    FlowTrack track;
    track.feature = ids[i];
    track.prev = prev_points[i];
    track.cur = next[i];
    tracks.push_back(track);
  }
  return tracks;
}

MotionConsistencyResult MotionConsistency::Test(std::vector<FlowTrack> tracks, const cv::Size& size,
                                                const cv::Mat& prev_exclusion,
                                                const cv::Mat& cur_exclusion,
                                                const cv::Mat& prev_depth,
                                                const PinholeCamera* camera) const {
  CheckMask(prev_exclusion, size, "the previous exclusion mask");
  CheckMask(cur_exclusion, size, "the current exclusion mask");
  if (!prev_depth.empty() && (prev_depth.type() != CV_32FC1 || prev_depth.size() != size)) {
    throw Error("MotionConsistency: the previous depth must be CV_32FC1 of the image size");
  }
  MotionConsistencyResult result;
  result.tracks = std::move(tracks);
  std::vector<double> flows;
  for (FlowTrack& track : result.tracks) {
    track.model_pair = !OnMask(prev_exclusion, track.prev) && !OnMask(cur_exclusion, track.cur) &&
                       !NearBorder(track.prev, size, options_.border_margin) &&
                       !NearBorder(track.cur, size, options_.border_margin);
    if (track.model_pair) {
      flows.push_back(std::hypot(track.cur.x - track.prev.x, track.cur.y - track.prev.y));
    }
  }
  // The scene models hold for the pinhole image, not the distorted one: they are fitted and
  // tested on undistorted positions (still pixels, as P = K), so their thresholds are in
  // undistorted pixels. Without distortion coefficients these are the flow's own positions.
  std::vector<cv::Point2f> undistorted_prev;
  std::vector<cv::Point2f> undistorted_cur;
  undistorted_prev.reserve(result.tracks.size());
  undistorted_cur.reserve(result.tracks.size());
  for (const FlowTrack& track : result.tracks) {
    undistorted_prev.push_back(track.prev);
    undistorted_cur.push_back(track.cur);
  }
  if (camera != nullptr) {
    undistorted_prev = camera->Undistort(undistorted_prev);
    undistorted_cur = camera->Undistort(undistorted_cur);
  }
  std::vector<cv::Point2f> model_prev;
  std::vector<cv::Point2f> model_cur;
  for (std::size_t i = 0; i < result.tracks.size(); ++i) {
    if (!result.tracks[i].model_pair) continue;
    model_prev.push_back(undistorted_prev[i]);
    model_cur.push_back(undistorted_cur[i]);
  }
  result.model_pairs = static_cast<int>(model_prev.size());
  if (!flows.empty()) {
    std::nth_element(flows.begin(), flows.begin() + flows.size() / 2, flows.end());
    result.median_flow = flows[flows.size() / 2];
  }
  if (result.model_pairs < options_.min_model_pairs) return result;
  if (camera != nullptr && !prev_depth.empty()) {
    TestReprojection(prev_depth, *camera, undistorted_prev, undistorted_cur, &result);
  }

  std::vector<uchar> f_inliers;
  const cv::Mat f =
      cv::findFundamentalMat(model_prev, model_cur, cv::FM_RANSAC, options_.ransac_threshold,
                             options_.ransac_confidence, f_inliers);
  int f_count = 0;
  if (f.rows == 3 && f.cols == 3) {
    result.fundamental = cv::Matx33d(f);
    f_count = cv::countNonZero(f_inliers);
    result.model = MotionModel::kFundamental;
    result.model_inliers = f_count;
  }
  if (options_.min_parallax_share > 0.0) {
    std::vector<uchar> h_inliers;
    const cv::Mat h =
        cv::findHomography(model_prev, model_cur, cv::RANSAC, options_.homography_threshold,
                           h_inliers, 2000, options_.ransac_confidence);
    if (h.rows == 3 && h.cols == 3) {
      const cv::Matx33d homography(h);
      // Parallax: static pairs the fundamental matrix explains and the homography does not.
      // Without enough of them the camera did not translate measurably, and the fundamental
      // matrix's epipole is free to line up with whatever moves.
      int parallax = 0;
      for (std::size_t i = 0; i < model_prev.size(); ++i) {
        if (f_count > 0 && f_inliers[i] &&
            TransferError(homography, model_prev[i], model_cur[i]) >
                options_.homography_threshold) {
          ++parallax;
        }
      }
      result.parallax_pairs = parallax;
      if (result.model == MotionModel::kNone ||
          parallax < options_.min_parallax_share * result.model_pairs) {
        result.homography = homography;
        result.model = MotionModel::kHomography;
        result.model_inliers = cv::countNonZero(h_inliers);
      }
    }
  }
  if (result.model == MotionModel::kNone) return result;

  const bool use_h = result.model == MotionModel::kHomography;
  const double threshold = use_h ? options_.homography_threshold : options_.epipolar_threshold;
  for (std::size_t i = 0; i < result.tracks.size(); ++i) {
    FlowTrack& track = result.tracks[i];
    const cv::Point2f& p = undistorted_prev[i];
    const cv::Point2f& c = undistorted_cur[i];
    track.residual =
        use_h ? TransferError(result.homography, p, c) : EpipolarDistance(result.fundamental, p, c);
    track.moving = track.residual > threshold;
    if (track.moving) ++result.moving_points;
  }
  return result;
}

void MotionConsistency::TestReprojection(const cv::Mat& prev_depth, const PinholeCamera& camera,
                                         const std::vector<cv::Point2f>& prev_pixels,
                                         const std::vector<cv::Point2f>& cur_pixels,
                                         MotionConsistencyResult* result) const {
  std::vector<FlowTrack>& tracks = result->tracks;

  // Previous points with a trustworthy depth: not on a depth edge, where a corner's pixel may
  // take either surface's depth.
  const cv::Rect inside(0, 0, prev_depth.cols, prev_depth.rows);
  std::vector<cv::Point3f> points(tracks.size());
  std::vector<bool> has_depth(tracks.size(), false);
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const cv::Point centre(cvRound(tracks[i].prev.x), cvRound(tracks[i].prev.y));
    const cv::Rect window = cv::Rect(centre.x - 1, centre.y - 1, 3, 3) & inside;
    if (window.area() < 9) continue;
    double low = 0.0, high = 0.0;
    cv::minMaxLoc(prev_depth(window), &low, &high);
    const float z = prev_depth.at<float>(centre);
    // NaN compares false everywhere, so a NaN depth (library callers may pass one) is rejected
    // explicitly rather than backprojected.
    if (!(z > 0.0f) || !std::isfinite(z) || !(low > 0.0) || !std::isfinite(high) ||
        high - low > options_.depth_edge * z) {
      continue;
    }
    const Eigen::Vector3d p =
        camera.Backproject(Eigen::Vector2d(prev_pixels[i].x, prev_pixels[i].y), z);
    points[i] = cv::Point3f(static_cast<float>(p.x()), static_cast<float>(p.y()),
                            static_cast<float>(p.z()));
    has_depth[i] = true;
  }
  // The anchored pairs when there are enough of them, else every model pair.
  int anchored = 0;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (has_depth[i] && tracks[i].model_pair && tracks[i].anchored) ++anchored;
  }
  result->pose_anchored = anchored >= options_.min_model_pairs;
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!has_depth[i] || !tracks[i].model_pair) continue;
    if (result->pose_anchored && !tracks[i].anchored) continue;
    object.push_back(points[i]);
    image.push_back(cur_pixels[i]);
  }
  if (static_cast<int>(object.size()) < options_.min_model_pairs) return;
  result->pose_pairs = static_cast<int>(object.size());
  const cv::Mat k = camera.K();
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(object, image, k, cv::noArray(), rvec, tvec, false, 100,
                          static_cast<float>(options_.reprojection_threshold),
                          options_.ransac_confidence, inliers, cv::SOLVEPNP_EPNP) ||
      static_cast<int>(inliers.size()) < options_.min_model_pairs / 2) {
    return;
  }
  std::vector<cv::Point3f> inlier_object;
  std::vector<cv::Point2f> inlier_image;
  for (const int i : inliers) {
    inlier_object.push_back(object[i]);
    inlier_image.push_back(image[i]);
  }
  cv::solvePnPRefineLM(inlier_object, inlier_image, k, cv::noArray(), rvec, tvec);
  result->pose_ok = true;
  result->pose_inliers = static_cast<int>(inliers.size());

  std::vector<cv::Point3f> tested;
  std::vector<std::size_t> slots;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!has_depth[i]) continue;
    tested.push_back(points[i]);
    slots.push_back(i);
  }
  if (tested.empty()) return;
  std::vector<cv::Point2f> projected;
  cv::projectPoints(tested, rvec, tvec, k, cv::noArray(), projected);
  for (std::size_t n = 0; n < slots.size(); ++n) {
    FlowTrack& track = tracks[slots[n]];
    const cv::Point2f& seen = cur_pixels[slots[n]];
    track.reprojection = std::hypot(projected[n].x - seen.x, projected[n].y - seen.y);
    track.reprojection_moving = track.reprojection > options_.reprojection_threshold;
    if (track.reprojection_moving) ++result->reprojection_moving;
  }
}

}  // namespace drvslam
