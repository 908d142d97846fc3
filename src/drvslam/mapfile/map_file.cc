#include "drvslam/mapfile/map_file.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "drvslam/core/error.h"
#include "drvslam/mapfile/byte_codec.h"

namespace drvslam {
namespace {

constexpr char kMagic[8] = {'D', 'R', 'V', 'S', 'M', 'A', 'P', '\0'};
// magic, version, section count, file length.
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8;
constexpr std::size_t kChecksumBytes = 4;
constexpr std::size_t kDescriptorBytes = 32;

constexpr uint32_t Tag(const char (&name)[5]) {
  return static_cast<uint32_t>(static_cast<unsigned char>(name[0])) |
         static_cast<uint32_t>(static_cast<unsigned char>(name[1])) << 8 |
         static_cast<uint32_t>(static_cast<unsigned char>(name[2])) << 16 |
         static_cast<uint32_t>(static_cast<unsigned char>(name[3])) << 24;
}

constexpr uint32_t kMetaTag = Tag("META");
constexpr uint32_t kKeyFramesTag = Tag("KFRM");
constexpr uint32_t kPointsTag = Tag("MPNT");
constexpr uint32_t kDenseTag = Tag("DENS");

std::string TagName(uint32_t tag) {
  std::string name;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((tag >> (8 * i)) & 0xffu);
    name.push_back(c >= 32 && c < 127 ? c : '?');
  }
  return name;
}

void WriteSe3(ByteWriter& out, const SE3& T) {
  const Eigen::Quaterniond& q = T.Quaternion();
  out.F64(q.w());
  out.F64(q.x());
  out.F64(q.y());
  out.F64(q.z());
  for (int i = 0; i < 3; ++i) out.F64(T.Translation()[i]);
}

SE3 ReadSe3(ByteReader& in) {
  const double w = in.F64(), x = in.F64(), y = in.F64(), z = in.F64();
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) t[i] = in.F64();
  const double norm = std::sqrt(w * w + x * x + y * y + z * z);
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6 || !t.allFinite()) {
    in.Fail("a pose is not a finite rigid transform");
  }
  return SE3(Eigen::Quaterniond(w, x, y, z), t);
}

void WriteCamera(ByteWriter& out, const CameraOptions& c) {
  for (const double v : {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.p1, c.p2, c.k3, c.bf}) out.F64(v);
  out.I32(c.width);
  out.I32(c.height);
}

CameraOptions ReadCamera(ByteReader& in) {
  CameraOptions c;
  for (double* v : {&c.fx, &c.fy, &c.cx, &c.cy, &c.k1, &c.k2, &c.p1, &c.p2, &c.k3, &c.bf}) {
    *v = in.F64();
  }
  c.width = in.I32();
  c.height = in.I32();
  return c;
}

void WriteMeta(ByteWriter& out, const MapFileContents& m) {
  out.U64(m.settings_digest);
  out.String(m.settings_text);
  WriteCamera(out, m.camera);
  out.I32(m.pyramid_levels);
  out.F64(m.pyramid_scale_factor);
  out.U64(m.vocabulary.words);
  out.U64(m.vocabulary.nodes);
  out.U64(m.vocabulary.hash);
  out.I64(m.next_keyframe_id);
  out.I64(m.next_map_point_id);
}

void ReadMeta(ByteReader& in, MapFileContents* m) {
  m->settings_digest = in.U64();
  m->settings_text = in.String();
  m->camera = ReadCamera(in);
  m->pyramid_levels = in.I32();
  m->pyramid_scale_factor = in.F64();
  m->vocabulary.words = in.U64();
  m->vocabulary.nodes = in.U64();
  m->vocabulary.hash = in.U64();
  m->next_keyframe_id = in.I64();
  m->next_map_point_id = in.I64();
  if (m->pyramid_levels < 1 || m->pyramid_levels > 32 || !(m->pyramid_scale_factor > 1.0)) {
    in.Fail("ORB pyramid of " + std::to_string(m->pyramid_levels) + " levels");
  }
}

void WritePairs(ByteWriter& out, const std::vector<std::pair<long, int>>& pairs) {
  out.U64(pairs.size());
  for (const auto& [id, value] : pairs) {
    out.I64(id);
    out.I32(value);
  }
}

std::vector<std::pair<long, int>> ReadPairs(ByteReader& in) {
  std::vector<std::pair<long, int>> pairs(in.Count(12));
  for (auto& [id, value] : pairs) {
    id = static_cast<long>(in.I64());
    value = in.I32();
  }
  return pairs;
}

void WriteKeyFrames(ByteWriter& out, const std::vector<KeyFrameRecord>& keyframes) {
  out.U64(keyframes.size());
  for (const KeyFrameRecord& k : keyframes) {
    out.I64(k.id);
    out.I64(k.frame_id);
    out.F64(k.timestamp);
    WriteSe3(out, k.T_cw);
    out.U64(k.keypoints.size());
    for (std::size_t i = 0; i < k.keypoints.size(); ++i) {
      const cv::KeyPoint& kp = k.keypoints[i];
      out.F32(kp.pt.x);
      out.F32(kp.pt.y);
      out.F32(kp.size);
      out.F32(kp.angle);
      out.F32(kp.response);
      out.I32(kp.octave);
      out.F32(k.depth[i]);
      out.Bytes(k.descriptors.ptr(static_cast<int>(i)), kDescriptorBytes);
    }
    WritePairs(out, k.connections);
    out.I64(k.parent_id);
  }
}

std::vector<KeyFrameRecord> ReadKeyFrames(ByteReader& in) {
  // The fixed part of a keyframe: ids, stamp, pose, three counts and the parent.
  std::vector<KeyFrameRecord> keyframes(in.Count(8 + 8 + 8 + 56 + 8 + 8 + 8));
  for (KeyFrameRecord& k : keyframes) {
    k.id = static_cast<long>(in.I64());
    k.frame_id = static_cast<long>(in.I64());
    k.timestamp = in.F64();
    k.T_cw = ReadSe3(in);
    const std::size_t n = in.Count(7 * 4 + kDescriptorBytes);
    k.keypoints.resize(n);
    k.depth.resize(n);
    k.descriptors.create(static_cast<int>(n), static_cast<int>(kDescriptorBytes), CV_8UC1);
    for (std::size_t i = 0; i < n; ++i) {
      cv::KeyPoint& kp = k.keypoints[i];
      kp.pt.x = in.F32();
      kp.pt.y = in.F32();
      kp.size = in.F32();
      kp.angle = in.F32();
      kp.response = in.F32();
      kp.octave = in.I32();
      k.depth[i] = in.F32();
      in.Bytes(k.descriptors.ptr(static_cast<int>(i)), kDescriptorBytes);
      if (!std::isfinite(kp.pt.x) || !std::isfinite(kp.pt.y) || !std::isfinite(k.depth[i])) {
        in.Fail("keyframe " + std::to_string(k.id) + ": keypoint " + std::to_string(i) +
                " is not finite");
      }
    }
    k.connections = ReadPairs(in);
    k.parent_id = static_cast<long>(in.I64());
  }
  return keyframes;
}

void WritePoints(ByteWriter& out, const std::vector<MapPointRecord>& points) {
  out.U64(points.size());
  for (const MapPointRecord& p : points) {
    out.I64(p.id);
    for (int i = 0; i < 3; ++i) out.F64(p.position[i]);
    out.I64(p.reference_keyframe_id);
    out.I32(p.visible);
    out.I32(p.found);
    WritePairs(out, p.observations);
  }
}

std::vector<MapPointRecord> ReadPoints(ByteReader& in) {
  std::vector<MapPointRecord> points(in.Count(8 + 24 + 8 + 4 + 4 + 8));
  for (MapPointRecord& p : points) {
    p.id = static_cast<long>(in.I64());
    for (int i = 0; i < 3; ++i) p.position[i] = in.F64();
    p.reference_keyframe_id = static_cast<long>(in.I64());
    p.visible = in.I32();
    p.found = in.I32();
    p.observations = ReadPairs(in);
    if (!p.position.allFinite()) {
      in.Fail("map point " + std::to_string(p.id) + " has no finite position");
    }
  }
  return points;
}

constexpr std::size_t kVoxelBytes = 4 + 12 + 3 + 2 + 4 + 4 + 2 + 2 + 1;

void WriteVoxels(ByteWriter& out, const std::vector<DenseVoxelRecord>& voxels) {
  out.U64(voxels.size());
  for (const DenseVoxelRecord& v : voxels) {
    out.I32(v.anchor);
    for (int i = 0; i < 3; ++i) out.F32(v.point.position[i]);
    out.U8(v.point.r);
    out.U8(v.point.g);
    out.U8(v.point.b);
    out.I16(v.point.label);
    out.I32(v.point.track);
    out.F32(v.weight);
    out.U16(v.views);
    out.I16(v.evidence);
    out.U8(v.span);
  }
}

std::vector<DenseVoxelRecord> ReadVoxels(ByteReader& in, std::size_t anchors) {
  std::vector<DenseVoxelRecord> voxels(in.Count(kVoxelBytes));
  for (DenseVoxelRecord& v : voxels) {
    v.anchor = in.I32();
    for (int i = 0; i < 3; ++i) v.point.position[i] = in.F32();
    v.point.r = in.U8();
    v.point.g = in.U8();
    v.point.b = in.U8();
    v.point.label = in.I16();
    v.point.track = in.I32();
    v.weight = in.F32();
    v.views = in.U16();
    v.evidence = in.I16();
    v.span = in.U8();
    if (v.anchor < 0 || static_cast<std::size_t>(v.anchor) >= anchors) {
      in.Fail("dense point anchored to " + std::to_string(v.anchor) + " of " +
              std::to_string(anchors) + " anchors");
    }
    if (!v.point.position.allFinite()) in.Fail("dense point is not finite");
  }
  return voxels;
}

void WriteDense(ByteWriter& out, const DenseMapSnapshot& dense) {
  out.U64(dense.anchors.size());
  for (const DenseAnchorRecord& anchor : dense.anchors) {
    out.I64(anchor.keyframe_id);
    WriteSe3(out, anchor.T_wc);
    out.F64(anchor.timestamp);
  }
  WriteVoxels(out, dense.coarse);
  WriteVoxels(out, dense.fine);
}

DenseMapSnapshot ReadDense(ByteReader& in) {
  DenseMapSnapshot dense;
  dense.anchors.resize(in.Count(8 + 56 + 8));
  for (DenseAnchorRecord& anchor : dense.anchors) {
    anchor.keyframe_id = static_cast<long>(in.I64());
    anchor.T_wc = ReadSe3(in);
    anchor.timestamp = in.F64();
  }
  dense.coarse = ReadVoxels(in, dense.anchors.size());
  dense.fine = ReadVoxels(in, dense.anchors.size());
  return dense;
}

// Ids unique, every reference names a stored keyframe, indices inside their keyframe.
void CheckReferences(const MapFileContents& m, const std::string& path) {
  const auto fail = [&path](const std::string& what) {
    throw Error(path + ": corrupt map file: " + what);
  };
  std::map<long, std::size_t> keypoints_of;
  for (const KeyFrameRecord& k : m.keyframes) {
    if (k.id < 0 || !keypoints_of.emplace(k.id, k.keypoints.size()).second) {
      fail("keyframe id " + std::to_string(k.id) + " is negative or repeated");
    }
    if (k.id >= m.next_keyframe_id) fail("keyframe id " + std::to_string(k.id) + " out of range");
    for (const cv::KeyPoint& kp : k.keypoints) {
      // Keypoints are saved inside the image or near it (a rolling-shutter correction moves
      // one near a border by a few pixels); one far outside would overflow the keyframe's
      // feature grid when the map is restored. An image's size on every side is the bound.
      const float width = static_cast<float>(m.camera.width);
      const float height = static_cast<float>(m.camera.height);
      if (!(kp.pt.x >= -width && kp.pt.x <= 2.0f * width && kp.pt.y >= -height &&
            kp.pt.y <= 2.0f * height)) {
        fail("keyframe " + std::to_string(k.id) + ": keypoint at (" + std::to_string(kp.pt.x) +
             ", " + std::to_string(kp.pt.y) + ") outside the " + std::to_string(m.camera.width) +
             "x" + std::to_string(m.camera.height) + " image by more than its size");
      }
      if (kp.octave < 0 || kp.octave >= m.pyramid_levels) {
        fail("keyframe " + std::to_string(k.id) + ": keypoint level " + std::to_string(kp.octave) +
             " outside the pyramid");
      }
    }
  }
  for (const KeyFrameRecord& k : m.keyframes) {
    if (k.parent_id >= 0 && (!keypoints_of.count(k.parent_id) || k.parent_id == k.id)) {
      fail("keyframe " + std::to_string(k.id) + ": parent " + std::to_string(k.parent_id) +
           " is not a keyframe of the map");
    }
    for (const auto& [id, weight] : k.connections) {
      if (!keypoints_of.count(id) || id == k.id || weight <= 0) {
        fail("keyframe " + std::to_string(k.id) + ": covisibility edge to " + std::to_string(id));
      }
    }
  }
  // The spanning tree has no cycle: every parent chain ends within the keyframe count.
  std::map<long, long> parent_of;
  for (const KeyFrameRecord& k : m.keyframes) parent_of[k.id] = k.parent_id;
  for (const KeyFrameRecord& k : m.keyframes) {
    long id = k.id;
    for (std::size_t step = 0; id >= 0; ++step) {
      if (step > m.keyframes.size())
        fail("the spanning tree has a cycle at keyframe " + std::to_string(k.id));
      id = parent_of[id];
    }
  }
  std::set<long> point_ids;
  for (const MapPointRecord& p : m.points) {
    if (p.id < 0 || p.id >= m.next_map_point_id || !point_ids.insert(p.id).second) {
      fail("map point id " + std::to_string(p.id) + " is out of range or repeated");
    }
    if (p.observations.empty() || !keypoints_of.count(p.reference_keyframe_id)) {
      fail("map point " + std::to_string(p.id) + " has no observation or reference keyframe");
    }
    for (const auto& [id, index] : p.observations) {
      const auto it = keypoints_of.find(id);
      if (it == keypoints_of.end() || index < 0 || static_cast<std::size_t>(index) >= it->second) {
        fail("map point " + std::to_string(p.id) + ": observation in keyframe " +
             std::to_string(id) + " at keypoint " + std::to_string(index));
      }
    }
  }
  if (m.dense) {
    for (const DenseAnchorRecord& anchor : m.dense->anchors) {
      if (anchor.keyframe_id >= 0 && !keypoints_of.count(anchor.keyframe_id)) {
        fail("dense map anchored to keyframe " + std::to_string(anchor.keyframe_id) +
             ", which the map does not hold");
      }
    }
  }
}

}  // namespace

std::string VocabularyIdentity::Describe() const {
  char hash_text[24];
  std::snprintf(hash_text, sizeof(hash_text), "%016" PRIx64, hash);
  return std::to_string(words) + " words, " + std::to_string(nodes) + " nodes, hash " + hash_text;
}

std::size_t WriteMapFile(const std::string& path, const MapFileContents& contents) {
  ByteWriter out;
  out.Bytes(kMagic, sizeof(kMagic));
  out.U32(kMapFileVersion);
  const uint32_t sections = contents.dense ? 4 : 3;
  out.U32(sections);
  const std::size_t length_at = out.Size();
  out.U64(0);  // the file length, patched below
  const auto section = [&out](uint32_t tag, const auto& write) {
    out.U32(tag);
    const std::size_t at = out.Size();
    out.U64(0);
    write();
    out.PatchU64(at, out.Size() - at - 8);
  };
  section(kMetaTag, [&] { WriteMeta(out, contents); });
  section(kKeyFramesTag, [&] { WriteKeyFrames(out, contents.keyframes); });
  section(kPointsTag, [&] { WritePoints(out, contents.points); });
  if (contents.dense) section(kDenseTag, [&] { WriteDense(out, *contents.dense); });
  out.PatchU64(length_at, out.Size() + kChecksumBytes);
  out.U32(Crc32(out.Buffer().data(), out.Size()));

  const std::string temporary = path + ".part";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (!file) throw Error(path + ": cannot write the map file (cannot create " + temporary + ")");
    file.write(out.Buffer().data(), static_cast<std::streamsize>(out.Size()));
    file.flush();
    if (!file) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(path + ": cannot write the map file (write failed)");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw Error(path + ": cannot write the map file (cannot replace it)");
  }
  return out.Size();
}

MapFileContents ReadMapFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path + ": cannot open the map file");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw Error(path + ": cannot read the map file");
  const std::size_t size = bytes.size();
  const std::size_t magic_seen = std::min(size, sizeof(kMagic));
  if (std::memcmp(bytes.data(), kMagic, magic_seen) != 0 || size == 0) {
    throw Error(path + ": not a drvslam map file (no DRVSMAP header)");
  }
  if (size < kHeaderBytes + kChecksumBytes) {
    throw Error(path + ": truncated map file: " + std::to_string(size) +
                " bytes, shorter than a header");
  }
  ByteReader header(bytes.data() + sizeof(kMagic), kHeaderBytes - sizeof(kMagic), path);
  const uint32_t version = header.U32();
  if (version != kMapFileVersion) {
    throw Error(path + ": map file format version " + std::to_string(version) +
                "; this build reads version " + std::to_string(kMapFileVersion));
  }
  const uint32_t sections = header.U32();
  const uint64_t length = header.U64();
  if (size < length) {
    throw Error(path + ": truncated map file: " + std::to_string(size) + " of " +
                std::to_string(length) + " bytes");
  }
  if (size > length) {
    throw Error(path + ": corrupt map file: " + std::to_string(size) +
                " bytes where the header says " + std::to_string(length));
  }
  ByteReader trailer(bytes.data() + size - kChecksumBytes, kChecksumBytes, path);
  const uint32_t stored_crc = trailer.U32();
  if (Crc32(bytes.data(), size - kChecksumBytes) != stored_crc) {
    throw Error(path + ": corrupt map file: checksum mismatch (the file was changed or damaged)");
  }

  MapFileContents contents;
  bool has_meta = false, has_keyframes = false, has_points = false;
  ByteReader body(bytes.data() + kHeaderBytes, size - kHeaderBytes - kChecksumBytes, path);
  for (uint32_t s = 0; s < sections; ++s) {
    const uint32_t tag = body.U32();
    const std::size_t payload = body.Count(1);
    ByteReader in(bytes.data() + kHeaderBytes + body.Position(), payload,
                  path + ": section " + TagName(tag));
    body.Skip(payload);
    if (tag == kMetaTag) {
      ReadMeta(in, &contents);
      has_meta = true;
    } else if (tag == kKeyFramesTag) {
      contents.keyframes = ReadKeyFrames(in);
      has_keyframes = true;
    } else if (tag == kPointsTag) {
      contents.points = ReadPoints(in);
      has_points = true;
    } else if (tag == kDenseTag) {
      contents.dense = ReadDense(in);
    } else {
      continue;  // a section of a later writer of this version: not needed to load the map
    }
    if (in.Remaining() != 0) in.Fail(std::to_string(in.Remaining()) + " bytes left over");
  }
  if (body.Remaining() != 0) body.Fail("data after the last section");
  if (!has_meta || !has_keyframes || !has_points) {
    throw Error(path + ": corrupt map file: a META, KFRM or MPNT section is missing");
  }
  CheckReferences(contents, path);
  return contents;
}

}  // namespace drvslam
