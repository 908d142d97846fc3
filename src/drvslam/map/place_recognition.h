// PlaceRecognition: what tracking needs of the bag-of-words machinery, which lives in a later
// module (loop/ implements it as Relocalizer; System wires it in). Tracking gives every new
// keyframe its bag of words through it, and asks it to find the camera again when tracking is
// lost. Used by the tracking thread only; implementations lock what they share.
#pragma once

#include "drvslam/map/frame.h"

namespace drvslam {

class PlaceRecognition {
 public:
  virtual ~PlaceRecognition() = default;

  // Fills frame.bow, frame.bow_features and sets frame.has_bow (nothing when already set).
  virtual void ComputeBow(Frame& frame) const = 0;

  // Searches the map for the frame's pose without a prior. On success the frame holds the pose
  // and its inlier matches in map_points (at least the implementation's inlier threshold), and
  // reference_keyframe is the keyframe it was found against; returns true. On failure the
  // frame's matches are cleared and false is returned.
  virtual bool Relocalize(Frame& frame) = 0;

  // The map is about to be cleared: forget every keyframe.
  virtual void Reset() = 0;
};

}  // namespace drvslam
