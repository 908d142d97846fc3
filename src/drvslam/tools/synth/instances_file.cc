#include "drvslam/tools/synth/instances_file.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/io/text_lines.h"

namespace drvslam {
namespace {

constexpr int kMaxInstanceId = 65535;

std::string ToFileName(std::string name) {
  for (char& ch : name) {
    if (ch == ' ') ch = '_';
  }
  return name;
}

std::string FromFileName(std::string name) {
  for (char& ch : name) {
    if (ch == '_') ch = ' ';
  }
  return name;
}

int ParseInt(const std::string& field, const std::string& where, const char* what) {
  int value = 0;
  const char* end = field.data() + field.size();
  const auto result = std::from_chars(field.data(), end, value);
  if (result.ec != std::errc() || result.ptr != end) {
    throw Error(where + ": " + what + " '" + field + "' is not an integer");
  }
  return value;
}

void CheckInstance(const SynthInstance& instance, const std::string& where) {
  if (instance.id < 1 || instance.id > kMaxInstanceId) {
    throw Error(where + ": instance id " + std::to_string(instance.id) + " is outside 1.." +
                std::to_string(kMaxInstanceId));
  }
  if (instance.class_name.empty()) throw Error(where + ": empty class name");
  for (const char ch : instance.class_name) {
    if (ch == '\t' || ch == '\n' || ch == '\r' || ch == ',' || ch == '#' || ch == '_') {
      throw Error(where + ": class name '" + instance.class_name +
                  "' holds a character the file cannot carry");
    }
  }
  if (instance.coco_id < -1 || instance.coco_id >= kCocoClassCount) {
    throw Error(where + ": COCO id " + std::to_string(instance.coco_id) + " is outside -1.." +
                std::to_string(kCocoClassCount - 1));
  }
  if (instance.coco_id >= 0 && CocoClassName(instance.coco_id) != instance.class_name) {
    throw Error(where + ": class '" + ToFileName(instance.class_name) +
                "' does not match COCO id " + std::to_string(instance.coco_id) + " ('" +
                ToFileName(CocoClassName(instance.coco_id)) + "')");
  }
}

}  // namespace

InstancesFile ReadInstancesFile(const std::string& path) {
  InstancesFile file;
  std::set<int> ids;
  ForEachDataLine(path, [&](int line_number, const std::vector<std::string>& fields) {
    const std::string where = path + ":" + std::to_string(line_number);
    const std::string& keyword = fields[0];
    if (keyword == "instance") {
      if (!file.frame_stamps.empty()) {
        throw Error(where + ": instance line after the first frame line");
      }
      if (fields.size() != 4) {
        throw Error(where + ": expected 'instance <id> <class_name> <coco_id>', found " +
                    std::to_string(fields.size()) + " fields");
      }
      SynthInstance instance;
      instance.id = ParseInt(fields[1], where, "instance id");
      instance.class_name = FromFileName(fields[2]);
      instance.coco_id = ParseInt(fields[3], where, "COCO id");
      CheckInstance(instance, where);
      if (!ids.insert(instance.id).second) {
        throw Error(where + ": duplicate instance id " + std::to_string(instance.id));
      }
      file.instances.push_back(instance);
    } else if (keyword == "frame") {
      const std::size_t count = file.instances.size();
      if (fields.size() != count + 2) {
        throw Error(where + ": expected a timestamp and " + std::to_string(count) +
                    " moving flags, found " + std::to_string(fields.size() - 1) + " values");
      }
      const double stamp = ParseNumber(fields[1], where);
      if (!std::isfinite(stamp))
        throw Error(where + ": timestamp '" + fields[1] + "' is not finite");
      if (!file.frame_stamps.empty() && stamp <= file.frame_stamps.back()) {
        throw Error(where + ": timestamp " + fields[1] + " does not increase");
      }
      std::vector<bool> flags(count);
      for (std::size_t k = 0; k < count; ++k) {
        const std::string& flag = fields[k + 2];
        if (flag != "0" && flag != "1") {
          throw Error(where + ": moving flag '" + flag + "' for instance " +
                      std::to_string(file.instances[k].id) + " is not 0 or 1");
        }
        flags[k] = flag == "1";
      }
      file.frame_stamps.push_back(stamp);
      file.moving.push_back(std::move(flags));
    } else {
      throw Error(where + ": unknown keyword '" + keyword + "' (expected 'instance' or 'frame')");
    }
  });
  return file;
}

std::string FormatInstancesFile(const InstancesFile& file) {
  std::string text =
      "# drvslam synthetic instances\n"
      "# instance <id> <class_name_with_spaces_as_underscores> <coco_id>\n";
  std::set<int> ids;
  for (const SynthInstance& instance : file.instances) {
    CheckInstance(instance, "instances");
    if (!ids.insert(instance.id).second) {
      throw Error("instances: duplicate instance id " + std::to_string(instance.id));
    }
    text += "instance " + std::to_string(instance.id) + " " + ToFileName(instance.class_name) +
            " " + std::to_string(instance.coco_id) + "\n";
  }
  if (file.moving.size() != file.frame_stamps.size()) {
    throw Error("instances: " + std::to_string(file.frame_stamps.size()) + " frame stamps but " +
                std::to_string(file.moving.size()) + " rows of moving flags");
  }
  text += "# frame <rgb timestamp> <moving flag 0/1 for each instance above, in the same order>\n";
  char stamp[64];
  for (std::size_t f = 0; f < file.frame_stamps.size(); ++f) {
    if (file.moving[f].size() != file.instances.size()) {
      throw Error("instances: frame " + std::to_string(f) + " has " +
                  std::to_string(file.moving[f].size()) + " moving flags for " +
                  std::to_string(file.instances.size()) + " instances");
    }
    std::snprintf(stamp, sizeof(stamp), "%.6f", file.frame_stamps[f]);
    text += "frame ";
    text += stamp;
    for (const bool flag : file.moving[f]) text += flag ? " 1" : " 0";
    text += "\n";
  }
  return text;
}

void WriteInstancesFile(const std::string& path, const InstancesFile& file) {
  const std::string text = FormatInstancesFile(file);
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  out << text;
  out.flush();
  if (!out) throw Error(path + ": write failed");
}

}  // namespace drvslam
