#include "drvslam/dense/point_cloud_io.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr std::size_t kPlyRecordBytes = 3 * sizeof(float) + 3 + sizeof(int16_t);
constexpr std::size_t kPcdRecordBytes = 3 * sizeof(float) + sizeof(uint32_t) + sizeof(int16_t);

template <typename T>
void Put(char** out, T value) {
  std::memcpy(*out, &value, sizeof(T));
  *out += sizeof(T);
}

void WriteFile(const std::string& path, const std::string& header, const std::vector<char>& body) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path + ": cannot open for writing");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(body.data(), static_cast<std::streamsize>(body.size()));
  if (!out) throw Error(path + ": write failed");
}

struct PlyProperty {
  std::string name;
  std::string type;
  std::size_t size = 0;
  std::size_t offset = 0;
};

std::size_t PlyTypeSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

}  // namespace

void WritePlyCloud(const std::string& path, const DenseCloud& cloud) {
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\ncomment drvslam dense map; label = class id"
         << " (-1 background)\nelement vertex " << cloud.size()
         << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
            "property uchar green\nproperty uchar blue\nproperty short label\nend_header\n";
  std::vector<char> body(cloud.size() * kPlyRecordBytes);
  char* out = body.data();
  for (const DensePoint& p : cloud) {
    for (int axis = 0; axis < 3; ++axis) Put(&out, p.position[axis]);
    Put(&out, p.r);
    Put(&out, p.g);
    Put(&out, p.b);
    Put(&out, p.label);
  }
  WriteFile(path, header.str(), body);
}

void WritePcdCloud(const std::string& path, const DenseCloud& cloud) {
  std::ostringstream header;
  header << "# .PCD v0.7 - Point Cloud Data file format (drvslam dense map)\nVERSION 0.7\n"
            "FIELDS x y z rgb label\nSIZE 4 4 4 4 2\nTYPE F F F F I\nCOUNT 1 1 1 1 1\n"
         << "WIDTH " << cloud.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS "
         << cloud.size() << "\nDATA binary\n";
  std::vector<char> body(cloud.size() * kPcdRecordBytes);
  char* out = body.data();
  for (const DensePoint& p : cloud) {
    for (int axis = 0; axis < 3; ++axis) Put(&out, p.position[axis]);
    // PCL packs colour as the bytes b, g, r, 0 of a 4-byte field.
    Put(&out, p.b);
    Put(&out, p.g);
    Put(&out, p.r);
    Put(&out, uint8_t{0});
    Put(&out, p.label);
  }
  WriteFile(path, header.str(), body);
}

DenseCloud ReadPlyCloud(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line) || line != "ply") throw Error(path + ": not a PLY file");
  std::size_t vertices = 0;
  bool in_vertex = false, seen_vertex = false, little_endian = false;
  std::vector<PlyProperty> properties;
  std::size_t record = 0;
  int line_number = 1;
  while (true) {
    if (!std::getline(in, line)) throw Error(path + ": header ends without end_header");
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
    if (keyword == "format") {
      std::string format;
      words >> format;
      little_endian = format == "binary_little_endian";
    } else if (keyword == "element") {
      std::string name;
      long long count = -1;
      words >> name >> count;
      if (!words || count < 0) throw Error(where + "malformed element line");
      if (seen_vertex && name != "vertex") {
        throw Error(where + "elements after the vertices are not supported");
      }
      in_vertex = name == "vertex";
      if (in_vertex) {
        if (seen_vertex) throw Error(where + "a second vertex element");
        seen_vertex = true;
        vertices = static_cast<std::size_t>(count);
      } else if (count > 0) {
        throw Error(where + "element '" + name + "' before the vertices is not supported");
      }
    } else if (keyword == "property") {
      if (!in_vertex) continue;
      PlyProperty property;
      words >> property.type >> property.name;
      if (!words || property.type == "list") {
        throw Error(where + "only fixed-size vertex properties are supported");
      }
      property.size = PlyTypeSize(property.type);
      if (property.size == 0) throw Error(where + "unknown type '" + property.type + "'");
      property.offset = record;
      record += property.size;
      properties.push_back(property);
    } else {
      throw Error(where + "unknown header keyword '" + keyword + "'");
    }
  }
  if (!little_endian) throw Error(path + ": only binary_little_endian PLY is read");
  const auto find = [&](const std::string& name) -> const PlyProperty* {
    for (const PlyProperty& p : properties) {
      if (p.name == name) return &p;
    }
    return nullptr;
  };
  const PlyProperty* xyz[3] = {find("x"), find("y"), find("z")};
  for (const PlyProperty* p : xyz) {
    if (p == nullptr || p->type.rfind("float", 0) != 0 || p->size != 4) {
      throw Error(path + ": vertices need float x, y and z");
    }
  }
  const PlyProperty* rgb[3] = {find("red"), find("green"), find("blue")};
  for (const PlyProperty* p : rgb) {
    if (p != nullptr && p->size != 1) throw Error(path + ": colours must be uchar");
  }
  const PlyProperty* label = find("label");
  if (label != nullptr && label->size != 2 && label->size != 4) {
    throw Error(path + ": label must be short or int");
  }
  if (vertices > 0 && record > 0 && vertices > (std::size_t{1} << 40) / record) {
    throw Error(path + ": vertex count too large");
  }
  std::vector<char> body(vertices * record);
  in.read(body.data(), static_cast<std::streamsize>(body.size()));
  if (static_cast<std::size_t>(in.gcount()) != body.size()) {
    throw Error(path + ": truncated: " + std::to_string(vertices) + " vertices announced");
  }
  DenseCloud cloud(vertices);
  for (std::size_t i = 0; i < vertices; ++i) {
    const char* base = body.data() + i * record;
    DensePoint& p = cloud[i];
    for (int axis = 0; axis < 3; ++axis) {
      std::memcpy(&p.position[axis], base + xyz[axis]->offset, sizeof(float));
    }
    if (rgb[0]) std::memcpy(&p.r, base + rgb[0]->offset, 1);
    if (rgb[1]) std::memcpy(&p.g, base + rgb[1]->offset, 1);
    if (rgb[2]) std::memcpy(&p.b, base + rgb[2]->offset, 1);
    if (label != nullptr) {
      if (label->size == 2) {
        std::memcpy(&p.label, base + label->offset, 2);
      } else {
        int32_t value = 0;
        std::memcpy(&value, base + label->offset, 4);
        p.label = static_cast<int16_t>(value);
      }
    }
  }
  return cloud;
}

}  // namespace drvslam
