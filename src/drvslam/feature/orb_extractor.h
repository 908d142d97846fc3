// OrbExtractor: ORB features for tracking. A scale pyramid, FAST corners with a fallback
// threshold for low-texture cells, a quad-tree spread of each level's share of the target
// count, intensity-centroid orientation and steered 256-bit BRIEF. A skip mask (e.g. pixels on
// moving objects) removes corners before they are distributed, so the count is met elsewhere.
// Not thread-safe: one extractor per thread; its buffers are reused from frame to frame.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/core/side_worker.h"
#include "drvslam/feature/fast_grid_detector.h"

namespace drvslam {

class OrbExtractor {
 public:
  // Calls options.Check() (throws drvslam::Error naming the bad key). With options.threads 2
  // the extractor owns one helper thread.
  explicit OrbExtractor(const OrbExtractorOptions& options);

  // gray: CV_8UC1. skip_mask: empty or CV_8UC1 of the same size (nonzero = no features there).
  // target_features <= 0 means options.n_features. Keypoints are in level-0 pixel coordinates,
  // octave = pyramid level, angle in degrees [0,360), size = 31 * scale of level,
  // response = FAST score, ordered by level, then row-major within a level.
  // descriptors: N x 32 CV_8UC1, row i for keypoint i. Throws drvslam::Error on a wrong image
  // type, an empty image, a mask of the wrong type or size, or null outputs. The result
  // depends only on the inputs (not on options.threads).
  void Extract(const cv::Mat& gray, const cv::Mat& skip_mask, int target_features,
               std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors);

  int Levels() const { return options_.n_levels; }
  const std::vector<float>& ScaleFactors() const { return scale_factors_; }
  const std::vector<float>& InvScaleFactors() const { return inv_scale_factors_; }
  const std::vector<float>& LevelSigma2() const { return level_sigma2_; }
  const std::vector<float>& InvLevelSigma2() const { return inv_level_sigma2_; }
  // The last image's levels (level 0 is a copy of it). A level smaller than 1x1 is empty.
  const std::vector<cv::Mat>& Pyramid() const { return pyramid_; }

  // Each level's share of `target` keypoints: geometric in 1 / scale, like ORB-SLAM, summing to
  // `target`.
  std::vector<int> LevelShares(int target) const;

 private:
  // Per-thread buffers, reused frame to frame.
  struct Scratch {
    cv::Mat smoothed;
    std::vector<uint16_t> smoothing_buffer;
    std::vector<cv::KeyPoint> fast;
  };
  void BuildPyramid(const cv::Mat& gray);
  // Calls work(level, scratch) for every level: levels are independent, so with a helper
  // thread both threads take levels from one list (SideWorker), each with its own scratch.
  void ForEachLevel(const std::function<void(int, Scratch&)>& work);
  void DetectCorners(const cv::Mat& skip_mask, int level, Scratch& scratch);
  void Describe(int level, int first_row, Scratch& scratch, std::vector<cv::KeyPoint>* keypoints,
                cv::Mat* descriptors) const;

  OrbExtractorOptions options_;
  FastGridParams fast_params_;
  std::vector<float> scale_factors_;
  std::vector<float> inv_scale_factors_;
  std::vector<float> level_sigma2_;
  std::vector<float> inv_level_sigma2_;
  std::vector<cv::Mat> pyramid_;
  // Reused per-frame buffers.
  std::array<Scratch, 2> scratch_;  // [0] for the calling thread, [1] for the helper
  std::vector<std::vector<cv::KeyPoint>> level_corners_;
  std::unique_ptr<SideWorker> helper_;  // null with one thread
};

}  // namespace drvslam
