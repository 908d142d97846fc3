// GroundTruthSegmenter: the exact instance masks of a sequence made by `drvslam synth`
// (masks/<colour image name>.png with 16-bit instance ids, and instances.txt naming each id's
// class and, per frame, whether it moves). It stands in for a network when the SLAM system is to
// be judged apart from detection errors, and gives the truth the dynamic module is checked with.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "drvslam/semantic/label_masks.h"
#include "drvslam/semantic/segmenter.h"
#include "drvslam/tools/synth/instances_file.h"

namespace drvslam {

class GroundTruthSegmenter : public Segmenter {
 public:
  // Reads sequence_dir/instances.txt and sequence_dir/rgb.txt (to name each frame's mask). Throws
  // drvslam::Error naming the file when either is missing or malformed.
  explicit GroundTruthSegmenter(const std::string& sequence_dir);

  // Thread-safe (reads files only). Instances get score 1, their instance id as source_id, their
  // class and the exact box of their mask. Throws Error naming the file when the frame's mask
  // is missing or not the image's size.
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) override;
  std::string Name() const override;
  // COCO-80 (class id = COCO id), then any classes outside COCO the file names, in file order.
  const std::vector<std::string>& ClassNames() const override { return class_names_; }

  const InstancesFile& Instances() const { return instances_; }
  // Whether instance `instance_id` moves in the frame at `timestamp` (nearest listed frame
  // within a millisecond); false when the id or the frame is not listed.
  bool IsMoving(int instance_id, double timestamp) const;
  // The mask file of the frame at `timestamp`; throws Error when rgb.txt lists no such frame.
  std::string MaskPath(double timestamp) const;

 private:
  std::string dir_;
  InstancesFile instances_;
  std::map<int, std::size_t> position_of_id_;  // index into instances_.instances
  std::vector<int> class_of_position_;         // class id of each of instances_.instances
  StampIndex mask_files_;
  std::map<double, std::size_t> frame_of_stamp_;  // index into instances_.frame_stamps
  std::vector<std::string> class_names_;
};

}  // namespace drvslam
