#include "drvslam/tools/eval/trajectory_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr int kWidth = 1600;
constexpr int kHeight = 760;
constexpr int kTitleHeight = 60;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kLabelScale = 0.5;
constexpr double kAxisTitleScale = 0.6;

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(225, 225, 225);
const cv::Scalar kGroundTruthColour(40, 40, 40);
const cv::Scalar kEstimateColour(200, 110, 20);  // blue
const cv::Scalar kErrorColour(40, 40, 220);      // red
const cv::Scalar kRmseColour(30, 150, 30);       // green

// A data interval mapped linearly onto a pixel interval (pixels may run backwards, as y does).
struct AxisMap {
  double data_min = 0.0;
  double data_max = 1.0;
  double pixel_min = 0.0;
  double pixel_max = 1.0;

  double ToPixel(double value) const {
    return pixel_min + (value - data_min) / (data_max - data_min) * (pixel_max - pixel_min);
  }
};

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `target` ticks over `range`.
double NiceStep(double range, int target) {
  const double raw = range / target;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double nice = fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0;
  return nice * power;
}

std::string TickLabel(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return text;
}

void PutText(cv::Mat& image, const std::string& text, cv::Point origin, double scale,
             const cv::Scalar& colour, int thickness = 1) {
  cv::putText(image, text, origin, kFont, scale, colour, thickness, cv::LINE_AA);
}

cv::Size TextSize(const std::string& text, double scale, int thickness = 1) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, thickness, &baseline);
}

// Draws text turned 90 degrees counter-clockwise, centred on `centre`.
void PutVerticalText(cv::Mat& image, const std::string& text, cv::Point centre, double scale) {
  const cv::Size size = TextSize(text, scale);
  cv::Mat strip(size.height + 8, size.width + 4, CV_8UC3, kWhite);
  PutText(strip, text, cv::Point(2, size.height + 2), scale, kBlack);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect target(centre.x - turned.cols / 2, centre.y - turned.rows / 2, turned.cols, turned.rows);
  target &= cv::Rect(0, 0, image.cols, image.rows);
  turned(cv::Rect(0, 0, target.width, target.height)).copyTo(image(target));
}

// Frame, grid, tick labels and axis titles of a plot area.
void DrawAxes(cv::Mat& image, const cv::Rect& area, const AxisMap& x, const AxisMap& y,
              const std::string& x_title, const std::string& y_title) {
  const double x_step = NiceStep(x.data_max - x.data_min, 6);
  const double y_step = NiceStep(y.data_max - y.data_min, 6);
  for (double v = std::ceil(x.data_min / x_step) * x_step; v <= x.data_max + 1e-9 * x_step;
       v += x_step) {
    const int px = static_cast<int>(std::lround(x.ToPixel(v)));
    cv::line(image, {px, area.y}, {px, area.y + area.height}, kGrid, 1);
    cv::line(image, {px, area.y + area.height}, {px, area.y + area.height + 5}, kBlack, 1);
    const std::string label = TickLabel(v, x_step);
    const cv::Size size = TextSize(label, kLabelScale);
    PutText(image, label, {px - size.width / 2, area.y + area.height + 10 + size.height},
            kLabelScale, kBlack);
  }
  for (double v = std::ceil(y.data_min / y_step) * y_step; v <= y.data_max + 1e-9 * y_step;
       v += y_step) {
    const int py = static_cast<int>(std::lround(y.ToPixel(v)));
    cv::line(image, {area.x, py}, {area.x + area.width, py}, kGrid, 1);
    cv::line(image, {area.x - 5, py}, {area.x, py}, kBlack, 1);
    const std::string label = TickLabel(v, y_step);
    const cv::Size size = TextSize(label, kLabelScale);
    PutText(image, label, {area.x - 9 - size.width, py + size.height / 2}, kLabelScale, kBlack);
  }
  cv::rectangle(image, area, kBlack, 1);
  const cv::Size x_size = TextSize(x_title, kAxisTitleScale);
  PutText(image, x_title, {area.x + (area.width - x_size.width) / 2, area.y + area.height + 50},
          kAxisTitleScale, kBlack);
  PutVerticalText(image, y_title, {area.x - 68, area.y + area.height / 2}, kAxisTitleScale);
}

// Splits a time series where consecutive samples are far apart (tracking lost), so that the
// plot shows a gap rather than a straight line across it.
std::vector<std::pair<std::size_t, std::size_t>> ContinuousRuns(const std::vector<double>& stamps) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  if (stamps.empty()) return runs;
  std::vector<double> gaps;
  for (std::size_t k = 1; k < stamps.size(); ++k) gaps.push_back(stamps[k] - stamps[k - 1]);
  double limit = 0.0;
  if (!gaps.empty()) {
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    limit = std::max(10.0 * sorted[sorted.size() / 2], 0.5);
  }
  std::size_t begin = 0;
  for (std::size_t k = 1; k < stamps.size(); ++k) {
    if (stamps[k] - stamps[k - 1] > limit) {
      runs.emplace_back(begin, k);
      begin = k;
    }
  }
  runs.emplace_back(begin, stamps.size());
  return runs;
}

void DrawSeries(cv::Mat& image, const std::vector<double>& stamps,
                const std::vector<cv::Point2d>& pixels, const cv::Scalar& colour, int thickness) {
  constexpr int kShift = 4;  // sub-pixel precision for smooth anti-aliased lines
  for (const auto& [begin, end] : ContinuousRuns(stamps)) {
    std::vector<cv::Point> run;
    for (std::size_t k = begin; k < end; ++k) {
      run.emplace_back(static_cast<int>(std::lround(pixels[k].x * (1 << kShift))),
                       static_cast<int>(std::lround(pixels[k].y * (1 << kShift))));
    }
    if (run.size() == 1) {
      cv::circle(image, run[0], thickness << kShift, colour, cv::FILLED, cv::LINE_AA, kShift);
    } else {
      cv::polylines(image, run, false, colour, thickness, cv::LINE_AA, kShift);
    }
  }
}

void DrawLegend(cv::Mat& image, cv::Point corner,
                const std::vector<std::pair<std::string, cv::Scalar>>& entries) {
  int width = 0;
  for (const auto& entry : entries) width = std::max(width, TextSize(entry.first, 0.55).width);
  const int row = 24;
  const cv::Rect box(corner.x, corner.y, width + 60, row * static_cast<int>(entries.size()) + 10);
  cv::rectangle(image, box, kWhite, cv::FILLED);
  cv::rectangle(image, box, cv::Scalar(160, 160, 160), 1);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const int y = corner.y + 17 + row * static_cast<int>(k);
    cv::line(image, {corner.x + 8, y}, {corner.x + 40, y}, entries[k].second, 3, cv::LINE_AA);
    PutText(image, entries[k].first, {corner.x + 48, y + 6}, 0.55, kBlack);
  }
}

// Two axes (of x, y, z) along which the ground truth extends most, in axis order.
std::array<int, 2> TopViewAxes(const Trajectory& gt) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const StampedPose& pose : gt) {
    low = low.cwiseMin(pose.T_wc.Translation());
    high = high.cwiseMax(pose.T_wc.Translation());
  }
  const Eigen::Vector3d extent = high - low;
  int smallest = 0;
  extent.minCoeff(&smallest);
  if (smallest == 0) return {1, 2};
  if (smallest == 1) return {0, 2};
  return {0, 1};
}

void DrawTopView(cv::Mat& image, const cv::Rect& area, const Trajectory& gt, const Trajectory& est,
                 const AteResult& ate) {
  const std::array<int, 2> axes = TopViewAxes(gt);
  std::vector<double> gt_stamps, est_stamps;
  std::vector<Eigen::Vector2d> gt_points, est_points;
  for (const StampedPose& pose : gt) {
    gt_stamps.push_back(pose.timestamp);
    const Eigen::Vector3d& p = pose.T_wc.Translation();
    gt_points.emplace_back(p(axes[0]), p(axes[1]));
  }
  for (const StampedPose& pose : est) {
    est_stamps.push_back(pose.timestamp);
    const Eigen::Vector3d p = ate.alignment.Apply(pose.T_wc.Translation());
    est_points.emplace_back(p(axes[0]), p(axes[1]));
  }

  // Equal metres per pixel on both axes, so that shapes are not distorted.
  Eigen::Vector2d low = gt_points.front(), high = gt_points.front();
  for (const auto* points : {&gt_points, &est_points}) {
    for (const Eigen::Vector2d& p : *points) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  const Eigen::Vector2d centre = 0.5 * (low + high);
  const double span_x = std::max(high.x() - low.x(), 1e-3) * 1.08;
  const double span_y = std::max(high.y() - low.y(), 1e-3) * 1.08;
  const double metres_per_pixel = std::max(span_x / area.width, span_y / area.height);
  const double half_x = 0.5 * area.width * metres_per_pixel;
  const double half_y = 0.5 * area.height * metres_per_pixel;
  const AxisMap x{centre.x() - half_x, centre.x() + half_x, static_cast<double>(area.x),
                  static_cast<double>(area.x + area.width)};
  const AxisMap y{centre.y() - half_y, centre.y() + half_y,
                  static_cast<double>(area.y + area.height), static_cast<double>(area.y)};
  const char* names[] = {"x", "y", "z"};
  DrawAxes(image, area, x, y, std::string(names[axes[0]]) + " [m]",
           std::string(names[axes[1]]) + " [m]");

  auto to_pixel = [&](const Eigen::Vector2d& p) {
    return cv::Point2d(x.ToPixel(p.x()), y.ToPixel(p.y()));
  };
  std::vector<cv::Point2d> gt_pixels, est_pixels;
  for (const Eigen::Vector2d& p : gt_points) gt_pixels.push_back(to_pixel(p));
  for (const Eigen::Vector2d& p : est_points) est_pixels.push_back(to_pixel(p));

  cv::Mat layer = image(area);
  const cv::Point2d origin(area.x, area.y);
  for (cv::Point2d& p : gt_pixels) p -= origin;
  for (cv::Point2d& p : est_pixels) p -= origin;
  DrawSeries(layer, gt_stamps, gt_pixels, kGroundTruthColour, 2);
  DrawSeries(layer, est_stamps, est_pixels, kEstimateColour, 1);
  // At most ~300 error segments: more would merge into a red smear.
  const std::size_t stride = std::max<std::size_t>(1, ate.matches.size() / 300);
  for (std::size_t k = 0; k < ate.matches.size(); k += stride) {
    const AteMatch& m = ate.matches[k];
    const cv::Point2d a = to_pixel({m.gt_position(axes[0]), m.gt_position(axes[1])}) - origin;
    const cv::Point2d b = to_pixel({m.est_aligned(axes[0]), m.est_aligned(axes[1])}) - origin;
    cv::line(layer, cv::Point(std::lround(a.x * 16), std::lround(a.y * 16)),
             cv::Point(std::lround(b.x * 16), std::lround(b.y * 16)), kErrorColour, 1, cv::LINE_AA,
             4);
  }
  DrawLegend(image, {area.x + 10, area.y + 10},
             {{"ground truth", kGroundTruthColour},
              {"estimate (aligned)", kEstimateColour},
              {stride == 1 ? "error" : "error (1 in " + std::to_string(stride) + " poses)",
               kErrorColour}});
}

void DrawErrorOverTime(cv::Mat& image, const cv::Rect& area, const AteResult& ate) {
  const double t0 = ate.matches.front().gt_stamp;
  const double duration = std::max(ate.matches.back().gt_stamp - t0, 1e-3);
  // Centimetres read better for the errors a working RGB-D system makes.
  const bool in_cm = ate.errors.max < 1.0;
  const double unit = in_cm ? 100.0 : 1.0;
  const double top = std::max(ate.errors.max * unit, in_cm ? 0.01 : 1e-4) * 1.1;
  const AxisMap x{0.0, duration, static_cast<double>(area.x),
                  static_cast<double>(area.x + area.width)};
  const AxisMap y{0.0, top, static_cast<double>(area.y + area.height), static_cast<double>(area.y)};
  DrawAxes(image, area, x, y, "time since first matched pose [s]",
           in_cm ? "ATE error [cm]" : "ATE error [m]");

  std::vector<double> stamps;
  std::vector<cv::Point2d> pixels;
  for (const AteMatch& m : ate.matches) {
    stamps.push_back(m.gt_stamp);
    pixels.emplace_back(x.ToPixel(m.gt_stamp - t0) - area.x, y.ToPixel(m.error * unit) - area.y);
  }
  cv::Mat layer = image(area);
  const int rmse_y = static_cast<int>(std::lround(y.ToPixel(ate.errors.rmse * unit)));
  for (int px = area.x; px < area.x + area.width; px += 14) {
    cv::line(image, {px, rmse_y}, {std::min(px + 7, area.x + area.width), rmse_y}, kRmseColour, 2);
  }
  DrawSeries(layer, stamps, pixels, kErrorColour, 1);
  DrawLegend(image, {area.x + 10, area.y + 10},
             {{"error per matched pose", kErrorColour}, {"rmse", kRmseColour}});
}

}  // namespace

cv::Mat RenderTrajectoryPlot(const Trajectory& gt, const Trajectory& est, const AteResult& ate) {
  if (gt.empty() || est.empty() || ate.matches.empty()) {
    throw Error("plot: nothing to draw (empty trajectory or no matched poses)");
  }
  cv::Mat image(kHeight, kWidth, CV_8UC3, kWhite);
  char title[256];
  std::snprintf(title, sizeof(title),
                "ATE rmse %.4f m (%.2f cm), %zu matched poses, coverage %.1f%% of %s%s",
                ate.errors.rmse, 100.0 * ate.errors.rmse, ate.matched, 100.0 * ate.coverage,
                ate.coverage_of == CoverageOf::kSequenceFrames ? "frames" : "GT poses",
                ate.with_scale ? (", scale " + std::to_string(ate.alignment.scale)).c_str() : "");
  const cv::Size title_size = TextSize(title, 0.8, 2);
  PutText(image, title, {(kWidth - title_size.width) / 2, 40}, 0.8, kBlack, 2);

  const int half = kWidth / 2;
  const cv::Rect left(95, kTitleHeight + 20, half - 95 - 25, kHeight - kTitleHeight - 20 - 80);
  const cv::Rect right(half + 95, left.y, half - 95 - 30, left.height);
  DrawTopView(image, left, gt, est, ate);
  DrawErrorOverTime(image, right, ate);
  return image;
}

void WriteTrajectoryPlot(const std::string& path, const Trajectory& gt, const Trajectory& est,
                         const AteResult& ate) {
  const cv::Mat image = RenderTrajectoryPlot(gt, est, ate);
  std::vector<uchar> png;
  if (!cv::imencode(".png", image, png)) throw Error(path + ": PNG encoding of the plot failed");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path + ": cannot open the --plot file for writing");
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  out.flush();
  if (!out) throw Error(path + ": writing the --plot file failed");
}

}  // namespace drvslam
