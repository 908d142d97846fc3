#include "drvslam/dynamic/feature_floor.h"

#include <algorithm>

namespace drvslam {

std::vector<int> KeepBack(std::vector<RemovalCandidate> removed, int kept, int floor) {
  std::vector<int> back;
  if (kept >= floor || removed.empty()) return back;
  std::sort(removed.begin(), removed.end(),
            [](const RemovalCandidate& a, const RemovalCandidate& b) {
              if (a.tier != b.tier) return a.tier < b.tier;
              if (a.evidence != b.evidence) return a.evidence < b.evidence;
              if (a.response != b.response) return a.response > b.response;
              return a.feature < b.feature;
            });
  const std::size_t wanted = std::min(removed.size(), static_cast<std::size_t>(floor - kept));
  back.reserve(wanted);
  for (std::size_t i = 0; i < wanted; ++i) back.push_back(removed[i].feature);
  return back;
}

}  // namespace drvslam
