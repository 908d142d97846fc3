#include "drvslam/tools/runner/cutout_sequence.h"

#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/semantic/segment_job.h"

namespace drvslam {

namespace fs = std::filesystem;

std::vector<std::string> DefaultCutoutPhotos() { return {"basketball1.png", "messi5.jpg"}; }

std::vector<std::string> CutoutPhotoPaths(const CutoutSequenceOptions& options) {
  std::vector<std::string> paths;
  for (const std::string& photo : options.photos) {
    const fs::path path =
        fs::path(photo).is_absolute() ? fs::path(photo) : fs::path(options.photo_dir) / photo;
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
      throw Error(path.string() +
                  ": photograph for the cut-out actors not found (Debian package opencv-doc)");
    }
    paths.push_back(path.string());
  }
  return paths;
}

CutoutSequence MakeCutoutSequence(Segmenter& segmenter, const CutoutSequenceOptions& options,
                                  const std::string& folder) {
  CutoutSequence made;
  made.cutouts_dir = (fs::path(folder) / "cutouts").string();
  made.sequence_dir = (fs::path(folder) / "sequence").string();
  SegmentJobOptions job;
  job.inputs = CutoutPhotoPaths(options);
  job.cutouts_dir = made.cutouts_dir;
  // Cut-outs of an earlier run would be drawn as actors too.
  std::error_code error;
  fs::remove_all(made.cutouts_dir, error);
  made.cutouts = RunSegmentJob(segmenter, job).cutouts;
  if (made.cutouts == 0) {
    std::string names;
    for (const std::string& input : job.inputs) names += (names.empty() ? "" : ", ") + input;
    throw Error(names + ": the segmenter found no person to cut out");
  }
  synth::SynthOptions synth_options = options.synth;
  synth_options.billboards = made.cutouts_dir;
  made.synth = synth::GenerateSequence(synth_options, made.sequence_dir);
  return made;
}

}  // namespace drvslam
