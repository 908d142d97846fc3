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
  if (options_.threads >= 2 && levels >= 2) helper_ = std::make_unique<SideWorker>("drv-orb");
}

void OrbExtractor::ForEachLevel(const std::function<void(int, Scratch&)>& work) {
  // Level 0 first: the largest item is started at once, the small ones fill in.
  if (!helper_) {
    for (int l = 0; l < options_.n_levels; ++l) work(l, scratch_[0]);
    return;
  }
  helper_->ForEach(options_.n_levels, [&](int l, int thread) { work(l, scratch_[thread]); });
}

void OrbExtractor::DetectCorners(const cv::Mat& skip_mask, int level, Scratch& scratch) {
  std::vector<cv::KeyPoint>& corners = level_corners_[level];
  corners.clear();
  if (pyramid_[level].empty()) return;
  const LevelSkipMask mask(skip_mask, scale_factors_[level]);
  DetectFastGrid(pyramid_[level], fast_params_, mask, &corners, &scratch.fast);
}

void OrbExtractor::Describe(int level, int first_row, Scratch& scratch,
                            std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors) const {
  const std::vector<cv::KeyPoint>& corners = level_corners_[level];
  if (corners.empty()) return;
  const cv::Mat& image = pyramid_[level];
  // BRIEF compares single pixels; smoothing first makes those tests robust to noise.
  SmoothGaussian7(image, &scratch.smoothed, &scratch.smoothing_buffer);
  const float scale = scale_factors_[level];
  int row = first_row;
  for (const cv::KeyPoint& corner : corners) {
    const int x = cvRound(corner.pt.x);
    const int y = cvRound(corner.pt.y);
    const float angle = IntensityCentroidAngle(image, x, y);
    ComputeSteeredBrief(scratch.smoothed, x, y, angle, descriptors->ptr<uint8_t>(row));
    (*keypoints)[row] = cv::KeyPoint(cv::Point2f(x * scale, y * scale), kPatchSize * scale, angle,
                                     corner.response, level);
    ++row;
  }
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

  // FAST on every level (independent of the shares), then coarse to fine: a level that cannot
  // fill its share passes the rest down to the finer levels, which have more corners to offer.
  ForEachLevel([&](int l, Scratch& scratch) { DetectCorners(skip_mask, l, scratch); });
  const std::vector<int> shares = LevelShares(target);
  int carry = 0;
  int total = 0;
  std::vector<int> first_row(levels, 0);
  for (int l = levels - 1; l >= 0; --l) {
    std::vector<cv::KeyPoint>& corners = level_corners_[l];
    const int want = shares[l] + carry;
    if (want > 0 && !pyramid_[l].empty()) {
      DistributeQuadtree(DetectionRegion(pyramid_[l].size(), kBorder), want, &corners);
    } else {
      corners.clear();
    }
    carry = want - static_cast<int>(corners.size());
    total += static_cast<int>(corners.size());
  }
  // Level 0's rows first: the output is ordered by level.
  for (int l = 1; l < levels; ++l) {
    first_row[l] = first_row[l - 1] + static_cast<int>(level_corners_[l - 1].size());
  }

  keypoints->assign(total, cv::KeyPoint());
  descriptors->create(total, kDescriptorBytes, CV_8UC1);
  ForEachLevel(
      [&](int l, Scratch& scratch) { Describe(l, first_row[l], scratch, keypoints, descriptors); });
}

}  // namespace drvslam
