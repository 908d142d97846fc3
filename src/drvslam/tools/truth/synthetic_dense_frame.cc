#include "drvslam/tools/truth/synthetic_dense_frame.h"

#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "drvslam/tools/synth/scene_builder.h"

namespace drvslam {

DenseFrame RenderDenseFrame(const synth::SynthSequence& sequence, int f) {
  const synth::RenderBuffers buffers = sequence.Render(f);
  DenseFrame frame;
  frame.frame_id = f;
  frame.timestamp = sequence.Stamp(f);
  frame.T_wc = sequence.Pose(f);
  frame.bgr = buffers.bgr;
  frame.depth = buffers.depth;
  const std::vector<SynthInstance> instances = sequence.Instances();
  const std::vector<bool> moving = sequence.MovingFlags(f);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    DenseInstance instance;
    instance.mask = buffers.instance == instances[k].id;
    if (cv::countNonZero(instance.mask) == 0) continue;
    instance.class_id = instances[k].coco_id;
    instance.track_id = instances[k].id;
    instance.potentially_moving = instances[k].id < synth::kFirstObjectInstanceId;
    instance.key_object = !instance.potentially_moving;
    instance.moving = moving[k];
    frame.instances.push_back(std::move(instance));
  }
  return frame;
}

}  // namespace drvslam
