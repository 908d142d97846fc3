// Dense-map files: binary little-endian PLY (x y z float, red green blue uchar, label short)
// and binary PCD v0.7 (x y z float, rgb packed the PCL way, label short). Both open in Open3D,
// CloudCompare, MeshLab and PCL; the label is the segmenter's class id (-1 = background).
#pragma once

#include <string>

#include "drvslam/dense/dense_point.h"

namespace drvslam {

// Throw Error naming the path when it cannot be written.
void WritePlyCloud(const std::string& path, const DenseCloud& cloud);
void WritePcdCloud(const std::string& path, const DenseCloud& cloud);

// Reads a binary little-endian PLY whose vertices have float x, y, z and optionally uchar red,
// green, blue and a short/int label (other properties of fixed size are skipped); tracks are
// -1. Throws Error naming the file for anything else or a truncated body.
DenseCloud ReadPlyCloud(const std::string& path);

}  // namespace drvslam
