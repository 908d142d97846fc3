// RenderDenseFrame: one frame of a synthetic sequence rendered in memory, as the dense mapper
// takes it, with the exact pose, masks and moving flags: for benchmarks and tests that measure
// the dense module apart from tracking and detection.
#pragma once

#include "drvslam/dense/dense_frame.h"
#include "drvslam/tools/synth/synth_sequence.h"

namespace drvslam {

// Actors are the potentially-moving instances, the static objects the key objects.
DenseFrame RenderDenseFrame(const synth::SynthSequence& sequence, int frame);

}  // namespace drvslam
