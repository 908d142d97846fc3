#include "drvslam/feature/quadtree_distribution.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace drvslam {
namespace {

// Corners sit on integer pixels, so a node narrower than a pixel in both directions holds one
// position; the cap only guards against degenerate input (e.g. duplicated corners).
constexpr int kMaxDepth = 24;

struct Node {
  float x0, y0, x1, y1;  // bounds, [x0, x1) x [y0, y1)
  int begin, end;        // its corners: a contiguous range of the corner array
  int depth;
  int id;  // creation order, the final tie-break
  int Count() const { return end - begin; }
};

// Lower priority = split later: deeper nodes after shallower ones, then sparser ones, then
// younger ones.
struct SplitLater {
  bool operator()(const Node& a, const Node& b) const {
    if (a.depth != b.depth) return a.depth > b.depth;
    if (a.Count() != b.Count()) return a.Count() < b.Count();
    return a.id > b.id;
  }
};

template <typename Pred>
int PartitionRange(std::vector<cv::KeyPoint>* corners, int begin, int end, Pred pred) {
  auto first = corners->begin();
  return static_cast<int>(std::partition(first + begin, first + end, pred) - first);
}

// Whether `a` is the stronger corner, with position as a total-order tie-break.
bool Stronger(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  if (a.response != b.response) return a.response > b.response;
  if (a.pt.y != b.pt.y) return a.pt.y < b.pt.y;
  return a.pt.x < b.pt.x;
}

}  // namespace

void DistributeQuadtree(const cv::Rect& region, int target, std::vector<cv::KeyPoint>* corners) {
  if (target <= 0) {
    corners->clear();
    return;
  }
  const int n = static_cast<int>(corners->size());
  if (n <= target) return;

  std::priority_queue<Node, std::vector<Node>, SplitLater> open;
  std::vector<Node> done;  // nodes no longer split: single corners and depth-capped ones
  int next_id = 0;
  auto add = [&](const Node& node) {
    if (node.Count() == 0) return;
    if (node.Count() == 1 || node.depth >= kMaxDepth) {
      done.push_back(node);
    } else {
      open.push(node);
    }
  };

  // Roots: roughly square columns, so that quadrants stay roughly square too.
  const int roots = std::max(1, static_cast<int>(std::lround(static_cast<double>(region.width) /
                                                             std::max(1, region.height))));
  const float root_width = static_cast<float>(region.width) / roots;
  int begin = 0;
  for (int r = 0; r < roots; ++r) {
    const float x0 = region.x + r * root_width;
    const float x1 = r + 1 == roots ? static_cast<float>(region.x + region.width + 1)
                                    : region.x + (r + 1) * root_width;
    const int end =
        r + 1 == roots ? n : PartitionRange(corners, begin, n, [x1](const cv::KeyPoint& kp) {
          return kp.pt.x < x1;
        });
    add({x0, static_cast<float>(region.y), x1, static_cast<float>(region.y + region.height + 1),
         begin, end, 0, next_id++});
    begin = end;
  }

  while (!open.empty() && static_cast<int>(done.size() + open.size()) < target) {
    const Node node = open.top();
    open.pop();
    const float xm = 0.5f * (node.x0 + node.x1);
    const float ym = 0.5f * (node.y0 + node.y1);
    const int mid = PartitionRange(corners, node.begin, node.end,
                                   [ym](const cv::KeyPoint& kp) { return kp.pt.y < ym; });
    auto left = [xm](const cv::KeyPoint& kp) { return kp.pt.x < xm; };
    const int top_mid = PartitionRange(corners, node.begin, mid, left);
    const int bottom_mid = PartitionRange(corners, mid, node.end, left);
    const int depth = node.depth + 1;
    add({node.x0, node.y0, xm, ym, node.begin, top_mid, depth, next_id++});
    add({xm, node.y0, node.x1, ym, top_mid, mid, depth, next_id++});
    add({node.x0, ym, xm, node.y1, mid, bottom_mid, depth, next_id++});
    add({xm, ym, node.x1, node.y1, bottom_mid, node.end, depth, next_id++});
  }
  while (!open.empty()) {
    done.push_back(open.top());
    open.pop();
  }

  std::vector<cv::KeyPoint> kept;
  kept.reserve(done.size());
  for (const Node& node : done) {
    auto first = corners->begin();
    kept.push_back(*std::min_element(first + node.begin, first + node.end, Stronger));
  }
  // The last split can overshoot by up to three nodes: drop the weakest of the extra corners.
  if (static_cast<int>(kept.size()) > target) {
    std::nth_element(kept.begin(), kept.begin() + target, kept.end(), Stronger);
    kept.resize(target);
  }
  // Row-major order: independent of how the tree happened to grow, and cache-friendly for the
  // per-corner work that follows.
  std::sort(kept.begin(), kept.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
    return a.pt.y != b.pt.y ? a.pt.y < b.pt.y : a.pt.x < b.pt.x;
  });
  corners->swap(kept);
}

}  // namespace drvslam
