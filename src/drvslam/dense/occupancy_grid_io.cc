#include "drvslam/dense/occupancy_grid_io.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>

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

}  // namespace

void WriteMapServerFiles(const OccupancyGrid& grid, const std::string& yaml_path,
                         const std::string& pgm_path) {
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

}  // namespace drvslam
