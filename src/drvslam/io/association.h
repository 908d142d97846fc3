// Timestamp association the way the TUM RGB-D benchmark's associate.py does it: every pair of
// stamps closer than max_difference (after adding offset to the second list) is a candidate;
// candidates are taken in order of increasing difference, each stamp used at most once; the
// result is sorted by the first stamp.
#pragma once

#include <cstddef>
#include <vector>

namespace drvslam {

struct StampMatch {
  std::size_t first;   // index into the first list
  std::size_t second;  // index into the second list
};

// Lists need not be sorted. O((n + m) log(n + m) + candidates).
std::vector<StampMatch> AssociateStamps(const std::vector<double>& first,
                                        const std::vector<double>& second, double offset,
                                        double max_difference);

}  // namespace drvslam
