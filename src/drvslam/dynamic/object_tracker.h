// ObjectIdTracker: step 2 of the paper's dynamic-object handling: the same object keeps one ID
// from frame to frame. Each current instance looks for the previous-frame instance that shares
// the most flow tracks with it (track started inside the previous mask and ended inside the
// current one; the Lucas-Kanade tracks of MotionConsistency are the feature matches). Same class
// and enough shared tracks: the ID is inherited; otherwise the instance gets a new ID; when the
// predecessor had no ID yet, both get the same new one. Each previous instance passes its ID on
// at most once per frame (strongest match first), so IDs stay unique within a frame.
#pragma once

#include <vector>

#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct IdAssignment {
  std::vector<int> predecessor;    // per current instance: index into previous, or -1
  std::vector<int> shared_tracks;  // per current instance: tracks shared with its best match
};

class ObjectIdTracker {
 public:
  // min_matches >= 1.
  explicit ObjectIdTracker(int min_matches);

  // Sets track_id of every current instance (and of a previous one that had none). Masks must
  // be CV_8UC1 of one size; tracks whose points fall outside it are ignored.
  IdAssignment Assign(std::vector<Instance>& previous, std::vector<Instance>& current,
                      const std::vector<FlowTrack>& tracks);

  // IDs handed out so far.
  int IssuedIds() const { return next_id_; }

 private:
  int min_matches_;
  int next_id_ = 0;
};

// Index of the instance whose mask holds pixel p (the first one, by index), or -1.
int InstanceAt(const std::vector<Instance>& instances, const cv::Point2f& p);

}  // namespace drvslam
