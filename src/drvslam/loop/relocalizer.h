// Relocalizer: finds a lost camera again in the existing map (ORB-SLAM2's relocalization),
// implementing tracking's PlaceRecognition interface. The frame's bag of words queries the
// keyframe database; each candidate keyframe is matched by bag of words, poses are found by PnP
// RANSAC (EPnP) on those matches (a second one on the matches the first left out, when enough
// are left to rival it), refined by pose-only optimization and extended by a guided projection
// search of the candidate's points.
// Unlike ORB-SLAM2, which takes the first candidate with enough inliers, every candidate is
// tried and the poses are compared (place_hypotheses.h): when two distinct places explain the
// frame almost equally well (repeated structure), neither is taken. Also computes the bags of
// words tracking attaches to new keyframes.
// Thread-safety: called by the tracking thread only; the database locks itself, and the
// vocabulary is immutable.
#pragma once

#include <memory>

#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/loop/keyframe_database.h"
#include "drvslam/loop/place_hypotheses.h"
#include "drvslam/loop/relocalization_options.h"
#include "drvslam/map/place_recognition.h"

namespace drvslam {

// Level of the vocabulary tree whose nodes make the direct index (FeatureVector): ORB-SLAM2's
// choice, 4 levels above the leaves, clamped to the root for shallow vocabularies.
int DirectIndexLevel(const BowVocabulary& vocabulary);

// What a relocalization attempt went through, for logs and tests.
struct RelocalizationReport {
  int candidates = 0;        // keyframes the database proposed
  int candidates_tried = 0;  // with enough BoW matches for PnP
  long keyframe_id = -1;     // the keyframe the pose was found against (-1: failed)
  int bow_matches = 0;       // with that keyframe
  int pnp_inliers = 0;
  int inliers = 0;     // after optimization and guided search
  int hypotheses = 0;  // poses that survived optimization, over all candidates
  PlaceChoice choice;  // how they were grouped into places and which was taken
};

class Relocalizer final : public PlaceRecognition {
 public:
  // `vocabulary` must not be null or empty; `database` must outlive the relocalizer. Throws
  // drvslam::Error on bad options or vocabulary.
  Relocalizer(std::shared_ptr<const BowVocabulary> vocabulary, KeyFrameDatabase& database,
              const RelocalizationOptions& options);

  // PlaceRecognition.
  void ComputeBow(Frame& frame) const override;
  bool Relocalize(Frame& frame) override;
  void Reset() override { database_.Clear(); }

  const RelocalizationReport& LastReport() const { return last_report_; }
  int Attempts() const { return attempts_; }
  // Attempts refused because two distinct places explained the frame almost equally well.
  int AmbiguousRejections() const { return ambiguous_rejections_; }

 private:
  // Pose-only optimization of the frame from its matches; outliers are removed from
  // frame.map_points. Returns the inliers.
  int OptimizeFramePose(Frame& frame) const;
  // PnP, optimization and guided search against one candidate: up to two hypotheses (the
  // second from the matches the first PnP left out) are added to `hypotheses`.
  void TryCandidate(Frame& frame, const std::shared_ptr<KeyFrame>& candidate,
                    const std::vector<std::shared_ptr<MapPoint>>& matches, int bow_matches,
                    std::vector<PlaceHypothesis>* hypotheses) const;
  // Pose and inliers from PnP inliers `slots` of `matches`, refined (optimization, guided
  // search); false when too few inliers survive.
  bool RefineHypothesis(Frame& frame, const KeyFrame& candidate,
                        const std::vector<std::shared_ptr<MapPoint>>& matches,
                        const std::vector<std::size_t>& inlier_slots, int* inliers) const;

  std::shared_ptr<const BowVocabulary> vocabulary_;
  KeyFrameDatabase& database_;
  RelocalizationOptions options_;
  int direct_index_level_;
  RelocalizationReport last_report_;
  int attempts_ = 0;
  int ambiguous_rejections_ = 0;
};

}  // namespace drvslam
