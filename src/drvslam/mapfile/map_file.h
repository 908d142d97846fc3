// Map files (`drvslam run --save-map`, System::SaveMap): the contents of a saved map and their
// versioned binary format.
//
// Layout (little-endian): the magic "DRVSMAP\0", u32 format version, u32 section count, u64
// file length; then per section a u32 tag, u64 payload length and the payload; then a CRC-32
// of every byte before it. Sections: META (settings digest and text, camera intrinsics, ORB
// pyramid, vocabulary identity, id counters), KFRM (keyframes: pose, keypoints, descriptors,
// keypoint depths, covisibility edges, spanning-tree parent), MPNT (map points: position,
// reference keyframe, match counters, observations) and, when dense mapping ran, DENS (the
// dense map, DenseMapSnapshot). Bags of words are not stored: the vocabulary the file names
// rebuilds them exactly from the descriptors. A reader skips sections it does not know, so a
// section may be added without a new version; any other change of layout raises the version.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/dense/dense_snapshot.h"

namespace drvslam {

inline constexpr uint32_t kMapFileVersion = 1;

// Which vocabulary a map's bags of words come from: its size and a hash of its tree.
struct VocabularyIdentity {
  uint64_t words = 0;
  uint64_t nodes = 0;
  uint64_t hash = 0;

  bool operator==(const VocabularyIdentity& other) const {
    return words == other.words && nodes == other.nodes && hash == other.hash;
  }
  bool operator!=(const VocabularyIdentity& other) const { return !(*this == other); }
  // "N words, M nodes, hash 0123abcd..."
  std::string Describe() const;
};

struct KeyFrameRecord {
  long id = 0;
  long frame_id = 0;
  double timestamp = 0.0;
  SE3 T_cw;
  std::vector<cv::KeyPoint> keypoints;            // as extracted (distorted pixels)
  cv::Mat descriptors;                            // N x 32 CV_8UC1
  std::vector<float> depth;                       // metres per keypoint, 0 = none
  std::vector<std::pair<long, int>> connections;  // covisible keyframe id, weight
  long parent_id = -1;                            // spanning tree; -1 = root
};

struct MapPointRecord {
  long id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  long reference_keyframe_id = -1;
  int visible = 1;
  int found = 1;
  std::vector<std::pair<long, int>> observations;  // keyframe id, keypoint index
};

struct MapFileContents {
  uint64_t settings_digest = 0;
  std::string settings_text;  // FormatSettings of the run that saved it
  CameraOptions camera;
  int pyramid_levels = 8;
  double pyramid_scale_factor = 1.2;
  VocabularyIdentity vocabulary;
  long next_keyframe_id = 0;
  long next_map_point_id = 0;
  std::vector<KeyFrameRecord> keyframes;
  std::vector<MapPointRecord> points;
  std::optional<DenseMapSnapshot> dense;
};

// Writes the file (through a temporary beside it, renamed at the end, so a failed save never
// leaves half a map under `path`). Returns the bytes written. Throws drvslam::Error naming the
// path when it cannot be written.
std::size_t WriteMapFile(const std::string& path, const MapFileContents& contents);

// Reads and checks a map file. Throws one drvslam::Error naming the path for: a missing or
// unreadable file, a file that is not a map file, another format version, a truncated file, a
// checksum mismatch, and contents that contradict themselves (counts, ids, indices).
MapFileContents ReadMapFile(const std::string& path);

}  // namespace drvslam
