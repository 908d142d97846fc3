// instances.txt of a synthetic sequence: the instance ids its masks/ hold, each with its COCO
// class, and for every frame which instances moved. The ground-truth segmentation backend and
// the evaluation read it; the generator writes it. Format (fixed):
//   # drvslam synthetic instances
//   # instance <id> <class_name_with_spaces_as_underscores> <coco_id>
//   instance 1 person 0
//   # frame <rgb timestamp> <moving flag 0/1 for each instance above, in the same order>
//   frame 1305031102.175304 1 ...
// Ids are 1..65535 (mask value; 0 is background); coco_id is -1 for a class outside COCO-80.
#pragma once

#include <string>
#include <vector>

namespace drvslam {

struct SynthInstance {
  int id = 0;
  std::string class_name;  // with spaces, as CocoClassName() spells it ("cell phone")
  int coco_id = -1;
};

struct InstancesFile {
  std::vector<SynthInstance> instances;
  std::vector<double> frame_stamps;
  std::vector<std::vector<bool>> moving;  // moving[frame][k] for instances[k]
};

// Strict reader: a malformed line, an unknown keyword, a duplicate or out-of-range id, a class
// name that does not match its COCO id, an instance line after the first frame line, a frame
// line with the wrong number of flags, a flag other than 0/1 or a stamp that does not increase
// is an Error naming the file and line.
InstancesFile ReadInstancesFile(const std::string& path);

// The file's text, stamps with 6 decimals (as the image names). Throws Error when the contents
// are inconsistent (duplicate ids, flag rows of the wrong length).
std::string FormatInstancesFile(const InstancesFile& file);
// Writes FormatInstancesFile() to `path`; throws Error when it cannot be written.
void WriteInstancesFile(const std::string& path, const InstancesFile& file);

}  // namespace drvslam
