#include "drvslam/semantic/class_table.h"

#include <spdlog/spdlog.h>

#include <cctype>
#include <utility>

namespace drvslam {
namespace {

std::vector<bool> Flags(const ClassTable& table, const std::vector<std::string>& listed,
                        const char* what) {
  std::vector<bool> flags(table.Size(), false);
  for (const std::string& name : listed) {
    const int id = table.Id(name);
    if (id < 0) {
      spdlog::debug("segmentation: {} class '{}' is not among the segmenter's {} classes", what,
                    name, table.Size());
      continue;
    }
    flags[id] = true;
  }
  return flags;
}

}  // namespace

std::string NormalizeClassName(const std::string& name) {
  std::string out;
  out.reserve(name.size());
  for (char c : name) {
    out.push_back(c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

ClassTable::ClassTable(std::vector<std::string> class_names,
                       const std::vector<std::string>& moving_classes,
                       const std::vector<std::string>& key_objects)
    : names_(std::move(class_names)) {
  moving_ = Flags(*this, moving_classes, "potentially moving");
  key_ = Flags(*this, key_objects, "key object");
}

ClassTable::ClassTable(std::vector<std::string> class_names, const SegmentationOptions& options)
    : ClassTable(std::move(class_names), options.moving_classes, options.key_objects) {}

bool ClassTable::IsPotentiallyMoving(int class_id) const {
  return class_id >= 0 && class_id < Size() && moving_[class_id];
}

bool ClassTable::IsKeyObject(int class_id) const {
  return class_id >= 0 && class_id < Size() && key_[class_id];
}

std::string ClassTable::Name(int class_id) const {
  if (class_id >= 0 && class_id < Size()) return names_[class_id];
  return "class" + std::to_string(class_id);
}

int ClassTable::Id(const std::string& name) const {
  const std::string wanted = NormalizeClassName(name);
  for (int i = 0; i < Size(); ++i) {
    if (NormalizeClassName(names_[i]) == wanted) return i;
  }
  return -1;
}

}  // namespace drvslam
