// The nearest-stamp lookup of the TUM benchmark's evaluate_rpe.py (find_closest_index), kept
// bit-for-bit, ties and all, because which poses RPE pairs up depends on it.
#pragma once

#include <cstddef>
#include <vector>

namespace drvslam {

// Bisection over the ascending list `sorted`: of the elements the bisection visits (and the
// first element), returns the index of the one nearest to `value`; on equal distance the one
// seen first wins, and an exact hit returns at once. Returns 0 for an empty list.
std::size_t FindClosestIndex(const std::vector<double>& sorted, double value);

}  // namespace drvslam
