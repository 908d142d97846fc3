// CheckMapConsistency: the invariants the map's two-sided links must keep, as a list of
// readable problems (empty when all hold). Tests call it in any build; local mapping asserts it
// after each keyframe in debug builds. Checked: every keyframe and point in the map is not bad;
// keyframe slot i holds point P iff P's observation of that keyframe has index i, and both are
// in the map; points have observations; spanning-tree links are mirrored (a keyframe is its
// parent's child) and every keyframe but the first has a live parent in the map.
// Only meaningful while no other thread changes the map.
#pragma once

#include <string>
#include <vector>

#include "drvslam/map/map.h"

namespace drvslam {

std::vector<std::string> CheckMapConsistency(const Map& map);

}  // namespace drvslam
