#include "drvslam/io/association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace drvslam {
namespace {

struct Candidate {
  double difference;
  double first_stamp;
  double second_stamp;
  std::size_t first;
  std::size_t second;
};

std::vector<std::size_t> SortedOrder(const std::vector<double>& stamps) {
  std::vector<std::size_t> order(stamps.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return stamps[a] < stamps[b]; });
  return order;
}

}  // namespace

std::vector<StampMatch> AssociateStamps(const std::vector<double>& first,
                                        const std::vector<double>& second, double offset,
                                        double max_difference) {
  const std::vector<std::size_t> first_order = SortedOrder(first);
  const std::vector<std::size_t> second_order = SortedOrder(second);

  // Sliding window over the sorted second list: only pairs inside the window are candidates.
  std::vector<Candidate> candidates;
  std::size_t window_begin = 0;
  for (const std::size_t i : first_order) {
    const double a = first[i];
    while (window_begin < second_order.size() &&
           second[second_order[window_begin]] + offset <= a - max_difference) {
      ++window_begin;
    }
    for (std::size_t k = window_begin; k < second_order.size(); ++k) {
      const std::size_t j = second_order[k];
      const double b = second[j];
      if (b + offset >= a + max_difference) break;
      const double difference = std::abs(a - (b + offset));
      if (difference < max_difference) candidates.push_back({difference, a, b, i, j});
    }
  }
  // Same order as sorting the (difference, a, b) tuples in Python.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.difference, x.first_stamp, x.second_stamp, x.first, x.second) <
           std::tie(y.difference, y.first_stamp, y.second_stamp, y.first, y.second);
  });

  std::vector<bool> first_used(first.size(), false);
  std::vector<bool> second_used(second.size(), false);
  std::vector<StampMatch> matches;
  for (const Candidate& c : candidates) {
    if (first_used[c.first] || second_used[c.second]) continue;
    first_used[c.first] = true;
    second_used[c.second] = true;
    matches.push_back({c.first, c.second});
  }
  std::sort(matches.begin(), matches.end(), [&](const StampMatch& x, const StampMatch& y) {
    return std::tie(first[x.first], x.first) < std::tie(first[y.first], y.first);
  });
  return matches;
}

}  // namespace drvslam
