// `--load-map` reads the file (ReadMapFile) and, once CheckMapCompatibility has found the map's
// camera and ORB pyramid to match the run's settings, rebuilds it (RestoreMap). The body stands
// in for those settings with the map's own camera and pyramid where they pass the settings'
// checks (else TUM fr3's), which is what a run whose settings match the map would have.
#include <cstring>
#include <string>

#include "drvslam/core/settings.h"
#include "drvslam/map/map.h"
#include "drvslam/mapfile/byte_codec.h"
#include "drvslam/mapfile/map_capture.h"
#include "drvslam/mapfile/map_file.h"
#include "fuzz_bodies/fuzz_bodies.h"
#include "fuzz_bodies/rejection.h"
#include "fuzz_bodies/scratch_file.h"

namespace drvslam::fuzz {
namespace {

// Where the header keeps the file length, and the checksum's size (map_file.h's layout).
constexpr std::size_t kLengthOffset = 8 + 4 + 4;
constexpr std::size_t kHeaderBytes = kLengthOffset + 8;
constexpr std::size_t kChecksumBytes = 4;

void PutLittleEndian(std::uint64_t value, std::size_t bytes, char* out) {
  for (std::size_t i = 0; i < bytes; ++i) out[i] = static_cast<char>((value >> (8 * i)) & 0xffu);
}

// The header's length and the trailing CRC-32 made to match the bytes.
void FixLengthAndChecksum(std::string* file) {
  if (file->size() < kHeaderBytes + kChecksumBytes) return;
  PutLittleEndian(file->size(), 8, &(*file)[kLengthOffset]);
  const std::size_t body = file->size() - kChecksumBytes;
  PutLittleEndian(Crc32(file->data(), body), kChecksumBytes, &(*file)[body]);
}

// The settings a run that accepts this map would have: its camera and pyramid when they are
// valid settings.
Settings MatchingSettings(const MapFileContents& contents) {
  Settings settings;
  AllowRejection([&] {
    contents.camera.Check();
    settings.camera = contents.camera;
  });
  OrbExtractorOptions orb = settings.orb;
  orb.n_levels = contents.pyramid_levels;
  orb.scale_factor = contents.pyramid_scale_factor;
  AllowRejection([&] {
    orb.Check();
    settings.orb = orb;
  });
  return settings;
}

}  // namespace

void RunMapFileBody(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  std::string file(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 1) FixLengthAndChecksum(&file);
  const std::string path = WriteScratchFile("map.bin", file);
  AllowRejection([&] {
    const MapFileContents contents = ReadMapFile(path);
    const Settings settings = MatchingSettings(contents);
    const auto geometry = std::make_shared<const SensorGeometry>(
        settings.camera, ScalePyramid(settings.orb.n_levels, settings.orb.scale_factor),
        settings.depth.CloseDepth(settings.camera));
    Map map;
    RestoreMap(
        contents, geometry, [](KeyFrame&) {}, &map, path);
  });
}

}  // namespace drvslam::fuzz
