// The 80 COCO class names in the order YOLO models index them (class id = position). Shared by
// the synthetic generator (actors and key objects carry COCO ids) and the segmenters.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace drvslam {

inline constexpr int kCocoClassCount = 80;

const std::array<std::string_view, kCocoClassCount>& CocoClassNames();

// Class id of a COCO name ("person" -> 0), or -1 when it is not one.
int CocoClassId(std::string_view name);

// Name of a class id, or "class<id>" outside 0..79.
std::string CocoClassName(int id);

// The classes that move by themselves (people, vehicles, animals): Segmentation.movingClasses'
// default, and what a synthetic sequence with movers of another class extends.
std::vector<std::string> DefaultMovingCocoClasses();

}  // namespace drvslam
