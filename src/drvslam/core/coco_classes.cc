#include "drvslam/core/coco_classes.h"

namespace drvslam {

const std::array<std::string_view, kCocoClassCount>& CocoClassNames() {
  static constexpr std::array<std::string_view, kCocoClassCount> kNames = {
      "person",        "bicycle",      "car",
      "motorcycle",    "airplane",     "bus",
      "train",         "truck",        "boat",
      "traffic light", "fire hydrant", "stop sign",
      "parking meter", "bench",        "bird",
      "cat",           "dog",          "horse",
      "sheep",         "cow",          "elephant",
      "bear",          "zebra",        "giraffe",
      "backpack",      "umbrella",     "handbag",
      "tie",           "suitcase",     "frisbee",
      "skis",          "snowboard",    "sports ball",
      "kite",          "baseball bat", "baseball glove",
      "skateboard",    "surfboard",    "tennis racket",
      "bottle",        "wine glass",   "cup",
      "fork",          "knife",        "spoon",
      "bowl",          "banana",       "apple",
      "sandwich",      "orange",       "broccoli",
      "carrot",        "hot dog",      "pizza",
      "donut",         "cake",         "chair",
      "couch",         "potted plant", "bed",
      "dining table",  "toilet",       "tv",
      "laptop",        "mouse",        "remote",
      "keyboard",      "cell phone",   "microwave",
      "oven",          "toaster",      "sink",
      "refrigerator",  "book",         "clock",
      "vase",          "scissors",     "teddy bear",
      "hair drier",    "toothbrush"};
  return kNames;
}

int CocoClassId(std::string_view name) {
  const auto& names = CocoClassNames();
  for (int i = 0; i < kCocoClassCount; ++i) {
    if (names[i] == name) return i;
  }
  return -1;
}

std::string CocoClassName(int id) {
  if (id < 0 || id >= kCocoClassCount) return "class" + std::to_string(id);
  return std::string(CocoClassNames()[id]);
}

std::vector<std::string> DefaultMovingCocoClasses() {
  return {"person", "bicycle", "car", "motorcycle", "bus",   "truck",
          "bird",   "cat",     "dog", "horse",      "sheep", "cow"};
}

}  // namespace drvslam
