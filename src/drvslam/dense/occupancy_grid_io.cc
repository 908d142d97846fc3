#include "drvslam/dense/occupancy_grid_io.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

unsigned char PgmValue(GridCell cell) {
  switch (cell) {
    case GridCell::kOccupied:
      return kPgmOccupied;
    case GridCell::kFree:
      return kPgmFree;
    default:
      return kPgmUnknown;
  }
}

GridCell CellOfPgm(unsigned char value, const std::string& path) {
  if (value == kPgmOccupied) return GridCell::kOccupied;
  if (value == kPgmFree) return GridCell::kFree;
  if (value == kPgmUnknown) return GridCell::kUnknown;
  throw Error(path + ": pixel value " + std::to_string(value) +
              " is none of the trinary map's 0, 205, 254");
}

// The numbers of a YAML flow list "[a, b, c]"; Error naming the file and key otherwise.
std::vector<double> NumberList(const std::string& text, const std::string& path,
                               const std::string& key) {
  const std::size_t open = text.find('[');
  const std::size_t close = text.rfind(']');
  if (open != 0 || close != text.size() - 1) {
    throw Error(path + ": " + key + " is not a [list] of numbers: " + text);
  }
  std::string inner = text.substr(1, close - 1);
  for (char& c : inner) c = c == ',' ? ' ' : c;
  std::istringstream in(inner);
  std::vector<double> values;
  for (double value; in >> value;) values.push_back(value);
  if (!in.eof()) throw Error(path + ": " + key + " holds something that is not a number: " + text);
  return values;
}

double Number(const std::string& text, const std::string& path, const std::string& key) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw Error(path + ": " + key + " is not a number: " + text);
  return value;
}

// The floor search's outcome as flat keys (lists of numbers, as the other keys).
void WriteFloorKeys(const FloorChoice& choice, std::ostream& yaml) {
  const FloorCandidate& floor = *choice.Floor();
  const std::vector<FloorCandidate> others = choice.RunnersUp();
  yaml << "# The floor's depth below the mean camera centre (m) and its dense points; the other\n"
       << "# horizontal planes found below the cameras, most points first.\n"
       << "drvslam_floor_depth_below_camera: " << floor.depth_below_camera << "\n"
       << "drvslam_floor_inliers: " << floor.plane.inliers << "\n"
       << "drvslam_floor_runner_up_depths: [";
  for (std::size_t i = 0; i < others.size(); ++i) {
    yaml << (i ? ", " : "") << others[i].depth_below_camera;
  }
  yaml << "]\ndrvslam_floor_runner_up_inliers: [";
  for (std::size_t i = 0; i < others.size(); ++i) {
    yaml << (i ? ", " : "") << others[i].plane.inliers;
  }
  yaml << "]\n";
}

}  // namespace

void WriteMapServerFiles(const OccupancyGrid& grid, const std::string& yaml_path,
                         const std::string& pgm_path, const FloorChoice* floor) {
  std::ofstream pgm(pgm_path, std::ios::binary);
  if (!pgm) throw Error(pgm_path + ": cannot open for writing");
  pgm << "P5\n# drvslam occupancy grid\n" << grid.width << " " << grid.height << "\n255\n";
  // Image rows run downwards, the grid's y upwards.
  for (int row = grid.height - 1; row >= 0; --row) {
    for (int column = 0; column < grid.width; ++column) pgm.put(PgmValue(grid.At(column, row)));
  }
  if (!pgm) throw Error(pgm_path + ": write failed");
  pgm.close();

  std::ofstream yaml(yaml_path);
  if (!yaml) throw Error(yaml_path + ": cannot open for writing");
  yaml << std::setprecision(9);
  yaml << "image: " << std::filesystem::path(pgm_path).filename().string() << "\n"
       << "mode: trinary\n"
       << "resolution: " << grid.resolution << "\n"
       << "origin: [" << grid.origin.x() << ", " << grid.origin.y() << ", 0.0]\n"
       << "negate: 0\n"
       << "occupied_thresh: 0.65\n"
       << "free_thresh: 0.196\n"
       << "# The grid frame (x, y on the floor, z up) in the trajectory's world frame, row-major.\n"
       << "drvslam_T_world_grid: [";
  for (int i = 0; i < 16; ++i) yaml << (i ? ", " : "") << grid.T_world_grid(i / 4, i % 4);
  yaml << "]\n";
  if (floor && floor->Floor()) WriteFloorKeys(*floor, yaml);
  if (!yaml) throw Error(yaml_path + ": write failed");
}

OccupancyGrid ReadMapServerPgm(const std::string& pgm_path, double resolution) {
  std::ifstream in(pgm_path, std::ios::binary);
  if (!in) throw Error(pgm_path + ": cannot open");
  std::string magic;
  in >> magic;
  if (magic != "P5") throw Error(pgm_path + ": not a binary PGM (P5)");
  auto next_number = [&]() {
    in >> std::ws;
    while (in.peek() == '#') {
      in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
      in >> std::ws;
    }
    int value = -1;
    in >> value;
    return value;
  };
  OccupancyGrid grid;
  grid.resolution = resolution;
  grid.width = next_number();
  grid.height = next_number();
  const int max_value = next_number();
  if (grid.width <= 0 || grid.height <= 0 || max_value != 255) {
    throw Error(pgm_path + ": bad PGM header (width, height, or a maximum other than 255)");
  }
  in.get();  // the single whitespace before the pixels
  grid.cells.resize(static_cast<std::size_t>(grid.width) * grid.height);
  for (int row = grid.height - 1; row >= 0; --row) {
    for (int column = 0; column < grid.width; ++column) {
      const int value = in.get();
      if (value == std::char_traits<char>::eof()) throw Error(pgm_path + ": truncated pixels");
      grid.cells[static_cast<std::size_t>(row) * grid.width + column] =
          CellOfPgm(static_cast<unsigned char>(value), pgm_path);
    }
  }
  return grid;
}

OccupancyGrid ReadMapServerFiles(const std::string& yaml_path) {
  std::ifstream in(yaml_path);
  if (!in) throw Error(yaml_path + ": cannot open");
  // "key: value" lines (comments and blank lines skipped), as WriteMapServerFiles writes them.
  std::map<std::string, std::string> values;
  for (std::string line; std::getline(in, line);) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) throw Error(yaml_path + ": not a 'key: value' line: " + line);
    std::string value = line.substr(colon + 1);
    value.erase(0, value.find_first_not_of(" \t"));
    value.erase(value.find_last_not_of(" \t\r") + 1);
    values[line.substr(start, colon - start)] = value;
  }
  for (const char* key : {"image", "resolution", "origin", "drvslam_T_world_grid"}) {
    if (values.count(key) == 0) throw Error(yaml_path + ": no " + key);
  }
  const double resolution = Number(values["resolution"], yaml_path, "resolution");
  if (!(resolution > 0.0)) throw Error(yaml_path + ": resolution must be positive");
  const std::vector<double> origin = NumberList(values["origin"], yaml_path, "origin");
  const std::vector<double> pose =
      NumberList(values["drvslam_T_world_grid"], yaml_path, "drvslam_T_world_grid");
  if (origin.size() != 3) throw Error(yaml_path + ": origin needs 3 numbers (x, y, yaw)");
  if (origin[2] != 0.0) throw Error(yaml_path + ": origin yaw must be 0 (drvslam writes 0)");
  if (pose.size() != 16) throw Error(yaml_path + ": drvslam_T_world_grid needs 16 numbers");
  const std::filesystem::path image =
      std::filesystem::path(yaml_path).parent_path() / values["image"];
  OccupancyGrid grid = ReadMapServerPgm(image.string(), resolution);
  grid.origin = {origin[0], origin[1]};
  for (int i = 0; i < 16; ++i) grid.T_world_grid(i / 4, i % 4) = pose[i];
  return grid;
}

}  // namespace drvslam
