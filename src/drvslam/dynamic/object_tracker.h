// ObjectIdTracker: step 2 of the paper's dynamic-object handling: the same object keeps one ID
// from frame to frame. Each current instance looks for the previous-frame instance that shares
// the most flow tracks with it (track started inside the previous mask and ended inside the
// current one; the Lucas-Kanade tracks of MotionConsistency are the feature matches). Same class
// and enough shared tracks: the ID is inherited; otherwise the instance gets a new ID; when the
// predecessor had no ID yet, both get the same new one. Each previous instance passes its ID on
// at most once per frame (strongest match first), so IDs stay unique within a frame.
// A current instance that already carries an ID (masks carried forward while segmentation lags)
// keeps it when a previous instance of its class has that ID.
// Memory (a flickering network): a previous instance that no current one continues is
// remembered for `memory_frames` frames, its mask carried frame to frame by the flow tracks
// (ObjectMaskCarrier); a current instance without a predecessor whose mask overlaps a
// remembered one of its class (IoU >= memory_iou) gets that ID back. A remembered object
// expires after `memory_frames` frames absent, or earlier when too few tracks carry its mask.
#pragma once

#include <vector>

#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/semantic/object_mask_carrier.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct IdAssignment {
  std::vector<int> predecessor;    // per current instance: index into previous, or -1
  std::vector<int> shared_tracks;  // per current instance: tracks shared with its best match
  // per current instance: -1, or, when its ID came back from memory, the frames it was absent
  // (0: present, but its flow tracks did not link it to its predecessor)
  std::vector<int> remembered;
};

class ObjectIdTracker {
 public:
  // min_matches >= 1, memory_frames >= 0 (0: no memory), memory_iou in (0, 1].
  explicit ObjectIdTracker(int min_matches, int memory_frames = 0, double memory_iou = 0.3);

  // Sets track_id of every current instance (and of a previous one that had none). Masks must
  // be CV_8UC1 of one size; tracks whose points fall outside it are ignored.
  IdAssignment Assign(std::vector<Instance>& previous, std::vector<Instance>& current,
                      const std::vector<FlowTrack>& tracks);

  // IDs handed out so far.
  int IssuedIds() const { return next_id_; }
  // Objects remembered now (absent from the latest frame, not yet expired).
  std::size_t Remembered() const { return lost_.size(); }

 private:
  struct Lost {
    Instance instance;  // mask carried to the latest frame
    int absent = 0;     // frames missing so far
  };
  // Carries the remembered objects (plus the previous instances no current one continued) to
  // the current frame and gives unmatched current instances their remembered IDs.
  void Remember(const std::vector<Instance>& previous, const std::vector<bool>& continued,
                std::vector<Instance>& current, const std::vector<FlowTrack>& tracks,
                IdAssignment& assignment);

  int min_matches_;
  int memory_frames_;
  double memory_iou_;
  ObjectMaskCarrier carrier_;
  std::vector<Lost> lost_;
  int next_id_ = 0;
};

// Intersection over union of two instances' masks (CV_8UC1 of one size), looked at only
// inside their boxes; 0 when both are empty.
double InstanceIoU(const Instance& a, const Instance& b);

// Index of the instance whose mask holds pixel p (the first one, by index), or -1.
int InstanceAt(const std::vector<Instance>& instances, const cv::Point2f& p);

}  // namespace drvslam
