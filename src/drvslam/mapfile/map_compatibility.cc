#include "drvslam/mapfile/map_compatibility.h"

#include <cmath>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/mapfile/byte_codec.h"

namespace drvslam {
namespace {

struct Difference {
  const char* key;
  double saved;
  double current;
  double relative;  // the measure compared with kIntrinsicsTolerance
};

std::string Describe(const Difference& d) {
  std::ostringstream text;
  text << d.key << " " << d.saved << " in the map, " << d.current << " now";
  return text.str();
}

}  // namespace

VocabularyIdentity IdentifyVocabulary(const BowVocabulary& vocabulary) {
  VocabularyIdentity identity;
  identity.words = vocabulary.WordCount();
  identity.nodes = vocabulary.NodeCount();
  uint64_t hash = kFnvOffsetBasis;
  for (std::size_t node = 0; node < vocabulary.NodeCount(); ++node) {
    const int id = static_cast<int>(node);
    const int32_t parent = vocabulary.NodeParent(id);
    const double weight = vocabulary.NodeWeight(id);
    hash = Fnv1a64(&parent, sizeof(parent), hash);
    hash = Fnv1a64(vocabulary.NodeDescriptor(id), 32, hash);
    hash = Fnv1a64(&weight, sizeof(weight), hash);
  }
  identity.hash = hash;
  return identity;
}

uint64_t SettingsDigest(const Settings& settings) {
  // The extractor's thread count does not change a single feature.
  Settings features = settings;
  features.orb.threads = OrbExtractorOptions().threads;
  const std::string text = FormatSettings(features);
  return Fnv1a64(text.data(), text.size());
}

std::vector<std::string> CheckMapCompatibility(const MapFileContents& contents,
                                               const Settings& settings,
                                               const BowVocabulary* vocabulary,
                                               const std::string& path) {
  const CameraOptions& saved = contents.camera;
  const CameraOptions& now = settings.camera;
  if (saved.width != now.width || saved.height != now.height) {
    throw Error(path + ": the map was made with " + std::to_string(saved.width) + "x" +
                std::to_string(saved.height) + " images; Camera.width/height is " +
                std::to_string(now.width) + "x" + std::to_string(now.height));
  }
  if (contents.pyramid_levels != settings.orb.n_levels ||
      std::abs(contents.pyramid_scale_factor - settings.orb.scale_factor) > 1e-9) {
    std::ostringstream text;
    text << path << ": the map's keypoints come from an ORB pyramid of " << contents.pyramid_levels
         << " levels at scale " << contents.pyramid_scale_factor
         << "; ORBextractor.nLevels/scaleFactor is " << settings.orb.n_levels << "/"
         << settings.orb.scale_factor;
    throw Error(text.str());
  }
  if (vocabulary == nullptr) {
    throw Error(path + ": the map needs its bag-of-words vocabulary (" +
                contents.vocabulary.Describe() +
                ") for relocalization, and none is loaded (Relocalization.enabled, "
                "Relocalization.vocabulary)");
  }
  const VocabularyIdentity loaded = IdentifyVocabulary(*vocabulary);
  if (loaded != contents.vocabulary) {
    throw Error(path + ": the map was saved with another vocabulary (" +
                contents.vocabulary.Describe() + "); the loaded one has " + loaded.Describe() +
                " (set Relocalization.vocabulary to the map's)");
  }
  const double width = now.width, height = now.height;
  const auto relative = [](double a, double b) {
    return std::abs(a - b) / std::max(std::abs(a), 1e-12);
  };
  const std::vector<Difference> differences = {
      {"Camera.fx", saved.fx, now.fx, relative(saved.fx, now.fx)},
      {"Camera.fy", saved.fy, now.fy, relative(saved.fy, now.fy)},
      {"Camera.cx", saved.cx, now.cx, std::abs(saved.cx - now.cx) / width},
      {"Camera.cy", saved.cy, now.cy, std::abs(saved.cy - now.cy) / height},
      {"Camera.bf", saved.bf, now.bf, relative(saved.bf, now.bf)},
      {"Camera.k1", saved.k1, now.k1, std::abs(saved.k1 - now.k1)},
      {"Camera.k2", saved.k2, now.k2, std::abs(saved.k2 - now.k2)},
      {"Camera.p1", saved.p1, now.p1, std::abs(saved.p1 - now.p1)},
      {"Camera.p2", saved.p2, now.p2, std::abs(saved.p2 - now.p2)},
      {"Camera.k3", saved.k3, now.k3, std::abs(saved.k3 - now.k3)},
  };
  std::vector<std::string> warnings;
  for (const Difference& d : differences) {
    if (d.relative > kIntrinsicsTolerance) {
      throw Error(path + ": the map was made with other camera intrinsics: " + Describe(d) +
                  " (more than the " +
                  std::to_string(static_cast<int>(kIntrinsicsTolerance * 100)) +
                  " % a map tolerates)");
    }
    if (d.saved != d.current) {
      warnings.push_back(path +
                         ": camera intrinsics differ slightly from the map's: " + Describe(d));
    }
  }
  // Intrinsics already warned about change the digest too; otherwise say that something else
  // (depth or ORB extractor keys) differs.
  if (warnings.empty() && contents.settings_digest != SettingsDigest(settings)) {
    warnings.push_back(path +
                       ": the map was made with other depth or ORB extractor settings (settings "
                       "digest differs)");
  }
  return warnings;
}

}  // namespace drvslam
