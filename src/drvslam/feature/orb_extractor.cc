#include "drvslam/feature/orb_extractor.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/feature/brief_pattern.h"
#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/feature/gaussian_smoothing.h"
#include "drvslam/feature/level_skip_mask.h"
#include "drvslam/feature/quadtree_distribution.h"
#include "drvslam/feature/steered_brief.h"

namespace drvslam {
namespace {

constexpr int kPatchSize = 2 * kBriefPatchRadius + 1;
// Corners keep one pixel more than the patch radius from the edge, so every orientation and
// rotated-pattern sample stays inside the level.
constexpr int kBorder = kBriefPatchRadius + 1;
constexpr int kFastCellSize = 32;

std::string MatDescription(const cv::Mat& m) {
  return std::to_string(m.cols) + "x" + std::to_string(m.rows) + " with " +
         std::to_string(m.channels()) + " channel(s) of depth " + std::to_string(m.depth());
}

void CheckInputs(const cv::Mat& gray, const cv::Mat& skip_mask,
                 const std::vector<cv::KeyPoint>* keypoints, const cv::Mat* descriptors) {
  if (keypoints == nullptr || descriptors == nullptr) {
    throw Error("OrbExtractor::Extract: keypoints and descriptors outputs must not be null");
  }
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw Error(
        "OrbExtractor::Extract: image must be a non-empty 8-bit gray image (CV_8UC1), got " +
        MatDescription(gray));
  }
  if (!skip_mask.empty() && (skip_mask.type() != CV_8UC1 || skip_mask.size() != gray.size())) {
    throw Error("OrbExtractor::Extract: skip mask must be empty or CV_8UC1 of the image size " +
                std::to_string(gray.cols) + "x" + std::to_string(gray.rows) + ", got " +
                MatDescription(skip_mask));
  }
}

}  // namespace

OrbExtractor::OrbExtractor(const OrbExtractorOptions& options) : options_(options) {
  options_.Check();
  fast_params_.ini_threshold = options_.ini_th_fast;
  fast_params_.min_threshold = options_.min_th_fast;
  fast_params_.border = kBorder;
  fast_params_.cell_size = kFastCellSize;
  const int levels = options_.n_levels;
  scale_factors_.resize(levels);
  inv_scale_factors_.resize(levels);
  level_sigma2_.resize(levels);
  inv_level_sigma2_.resize(levels);
  for (int l = 0; l < levels; ++l) {
    const double scale = std::pow(options_.scale_factor, l);
    scale_factors_[l] = static_cast<float>(scale);
    inv_scale_factors_[l] = static_cast<float>(1.0 / scale);
    level_sigma2_[l] = static_cast<float>(scale * scale);
    inv_level_sigma2_[l] = static_cast<float>(1.0 / (scale * scale));
  }
  pyramid_.resize(levels);
  level_corners_.resize(levels);
  GetBriefPattern();  // build the table now rather than inside the first frame
}

std::vector<int> OrbExtractor::LevelShares(int target) const {
  const int levels = options_.n_levels;
  const double f = 1.0 / options_.scale_factor;
  // Level l gets target * f^l / sum_k f^k.
  const double first = target * (1.0 - f) / (1.0 - std::pow(f, levels));
  // Rounding the running total (not each share) keeps every share >= 0 and the sum exact.
  std::vector<int> shares(levels, 0);
  double cumulative = 0.0;
  int assigned = 0;
  for (int l = 0; l < levels; ++l) {
    cumulative += first * std::pow(f, l);
    const int upto = l + 1 == levels ? target : static_cast<int>(std::lround(cumulative));
    shares[l] = std::max(0, upto - assigned);
    assigned += shares[l];
  }
  return shares;
}

void OrbExtractor::BuildPyramid(const cv::Mat& gray) {
  gray.copyTo(pyramid_[0]);
  for (int l = 1; l < options_.n_levels; ++l) {
    const cv::Size size(cvRound(gray.cols * inv_scale_factors_[l]),
                        cvRound(gray.rows * inv_scale_factors_[l]));
    if (size.width < 1 || size.height < 1 || pyramid_[l - 1].empty()) {
      pyramid_[l].release();
      continue;
    }
    // Each level from the previous one, bilinear, as ORB-SLAM builds its pyramid: the small
    // steps keep the slight aliasing of bilinear downsampling small, at a fraction of the cost
    // of area-averaging every level from level 0.
    cv::resize(pyramid_[l - 1], pyramid_[l], size, 0, 0, cv::INTER_LINEAR);
  }
}

void OrbExtractor::Extract(const cv::Mat& gray, const cv::Mat& skip_mask, int target_features,
                           std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors) {
  CheckInputs(gray, skip_mask, keypoints, descriptors);
  const int target = target_features > 0 ? target_features : options_.n_features;
  const int levels = options_.n_levels;
  BuildPyramid(gray);

  // Coarse to fine: a level that cannot fill its share passes the rest down to the finer
  // levels, which have more corners to offer.
  const std::vector<int> shares = LevelShares(target);
  int carry = 0;
  int total = 0;
  for (int l = levels - 1; l >= 0; --l) {
    std::vector<cv::KeyPoint>& corners = level_corners_[l];
    corners.clear();
    const int want = shares[l] + carry;
    if (!pyramid_[l].empty() && want > 0) {
      const LevelSkipMask mask(skip_mask, scale_factors_[l]);
      DetectFastGrid(pyramid_[l], fast_params_, mask, &corners, &fast_scratch_);
      DistributeQuadtree(DetectionRegion(pyramid_[l].size(), kBorder), want, &corners);
    }
    carry = want - static_cast<int>(corners.size());
    total += static_cast<int>(corners.size());
  }

  keypoints->clear();
  keypoints->reserve(total);
  descriptors->create(total, kDescriptorBytes, CV_8UC1);
  int row = 0;
  for (int l = 0; l < levels; ++l) {
    const std::vector<cv::KeyPoint>& corners = level_corners_[l];
    if (corners.empty()) continue;
    const cv::Mat& level = pyramid_[l];
    // BRIEF compares single pixels; smoothing first makes those tests robust to noise.
    SmoothGaussian7(level, &smoothed_, &smoothing_buffer_);
    const float scale = scale_factors_[l];
    for (const cv::KeyPoint& corner : corners) {
      const int x = cvRound(corner.pt.x);
      const int y = cvRound(corner.pt.y);
      const float angle = IntensityCentroidAngle(level, x, y);
      ComputeSteeredBrief(smoothed_, x, y, angle, descriptors->ptr<uint8_t>(row++));
      keypoints->emplace_back(cv::Point2f(x * scale, y * scale), kPatchSize * scale, angle,
                              corner.response, l);
    }
  }
}

}  // namespace drvslam
