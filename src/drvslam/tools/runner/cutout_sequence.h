// MakeCutoutSequence: a synthetic sequence whose actors a real network can see. People are cut
// out of photographs with a YOLO-seg model (what `drvslam segment --cutouts` writes) and drawn
// as billboard actors (what `drvslam synth --billboards` renders), so the sequence can be run
// with `--segmenter yolo` instead of its ground-truth masks.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "drvslam/semantic/segmenter.h"
#include "drvslam/tools/synth/synth_generator.h"

namespace drvslam {

// The opencv-doc photographs the cut-outs come from: two still photos with large people in
// them (sorted by name, the walking scenarios' two actors get one each).
std::vector<std::string> DefaultCutoutPhotos();

struct CutoutSequenceOptions {
  // Photographs to cut people out of; relative names are taken in photo_dir.
  std::vector<std::string> photos = DefaultCutoutPhotos();
  std::string photo_dir = synth::kOpenCvDocDataFolder;
  // The sequence; its `billboards` is set to the cut-outs folder.
  synth::SynthOptions synth;
};

struct CutoutSequence {
  std::string cutouts_dir;   // FOLDER/cutouts
  std::string sequence_dir;  // FOLDER/sequence
  std::size_t cutouts = 0;
  synth::SynthSummary synth;
};

// Full paths of the photographs; throws drvslam::Error naming the first one that is missing.
std::vector<std::string> CutoutPhotoPaths(const CutoutSequenceOptions& options);

// Cuts the people out of the photographs with `segmenter` into FOLDER/cutouts and synthesizes
// the sequence into FOLDER/sequence. Throws drvslam::Error naming the photograph when one is
// missing, and naming the photographs when no person was found in them.
CutoutSequence MakeCutoutSequence(Segmenter& segmenter, const CutoutSequenceOptions& options,
                                  const std::string& folder);

}  // namespace drvslam
