// ClassTable: what each class of a segmenter means to the SLAM system. Potentially moving classes
// (people, animals, vehicles) are checked for motion and their features removed when they move;
// key objects are kept and enhanced in the dense map; every other class is static background.
#pragma once

#include <string>
#include <vector>

#include "drvslam/semantic/segmentation_options.h"

namespace drvslam {

class ClassTable {
 public:
  // `class_names` is the segmenter's id -> name table. Names in the option lists match ignoring
  // case, with '_' and ' ' equal ("cell_phone" = "cell phone"); listed names the table lacks are
  // logged once and otherwise ignored, so one settings file serves models with other classes.
  ClassTable(std::vector<std::string> class_names, const std::vector<std::string>& moving_classes,
             const std::vector<std::string>& key_objects);
  ClassTable(std::vector<std::string> class_names, const SegmentationOptions& options);

  bool IsPotentiallyMoving(int class_id) const;
  bool IsKeyObject(int class_id) const;
  // Neither potentially moving nor a key object (also true for ids outside the table).
  bool IsStatic(int class_id) const {
    return !IsPotentiallyMoving(class_id) && !IsKeyObject(class_id);
  }

  int Size() const { return static_cast<int>(names_.size()); }
  // Name of an id, or "class<id>" outside the table.
  std::string Name(int class_id) const;
  // Id of a name (same matching rules as above), -1 when absent.
  int Id(const std::string& name) const;

 private:
  std::vector<std::string> names_;
  std::vector<bool> moving_;
  std::vector<bool> key_;
};

// Lower-case with '_' turned into ' ', the form class names are compared in.
std::string NormalizeClassName(const std::string& name);

}  // namespace drvslam
