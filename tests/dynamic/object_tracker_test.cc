// Object IDs: two people crossing in front of each other keep their IDs (real flow tracks on
// rendered images), and the paper's rules for class, match count and predecessors without IDs.
#include "drvslam/dynamic/object_tracker.h"

#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "plane_scene.h"

namespace drvslam {
namespace {

using test::Camera;
using test::Plane;

Instance Box(int class_id, const cv::Rect& box, cv::Size size = {200, 100}) {
  Instance instance;
  instance.class_id = class_id;
  instance.box = box;
  instance.mask = cv::Mat::zeros(size, CV_8UC1);
  instance.mask(box).setTo(255);
  return instance;
}

std::vector<FlowTrack> Shifted(const cv::Rect& from, const cv::Point2f& shift, int count) {
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < count; ++i) {
    FlowTrack track;
    track.prev = cv::Point2f(from.x + 1.0f + (i * 7) % (from.width - 2),
                             from.y + 1.0f + (i * 3) % (from.height - 2));
    track.cur = track.prev + shift;
    tracks.push_back(track);
  }
  return tracks;
}

TEST(ObjectIdTrackerTest, TwoPeopleCrossingKeepTheirIds) {
  // A (nearer, narrower) walks right, B (farther, taller) walks left; the camera stands still.
  std::vector<Plane> scene = {{5.0, {-4, -3, 8, 6}, 1, 0.06},
                              {2.5, {-0.8, -0.6, 0.3, 1.0}, 2, 0.03},
                              {3.0, {0.5, -0.9, 0.45, 1.6}, 3, 0.03}};
  DynamicOptions options;
  const MotionConsistency consistency(options);
  ObjectIdTracker tracker(options.min_id_matches);
  const Camera camera;
  std::vector<Instance> previous;
  FlowImage previous_flow;
  std::vector<cv::Point2f> previous_points;
  std::map<int, int> id_of_person;  // source_id (plane) -> track id
  int frames_with_both = 0;
  int frames_overlapping = 0;
  for (int f = 0; f < 24; ++f) {
    const double a_x = 0.05 * f;
    const double b_x = -0.06 * f;
    const test::Rendered image = test::Render(scene, camera, {{0, 0}, {a_x, 0}, {b_x, 0}});
    std::vector<Instance> current = test::InstancesOf(image, {1, 2});
    const FlowImage flow = BuildFlowImage(image.gray, options);
    std::vector<FlowTrack> tracks;
    if (!previous_flow.Empty()) {
      std::vector<int> ids(previous_points.size());
      for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
      tracks = consistency.Run(previous_flow, flow, previous_points, ids, {}, {}).tracks;
    }
    tracker.Assign(previous, current, tracks);
    for (const Instance& instance : current) {
      ASSERT_GE(instance.track_id, 0);
      const auto known = id_of_person.emplace(instance.source_id, instance.track_id);
      EXPECT_EQ(known.first->second, instance.track_id)
          << "person " << instance.source_id << " changed ID at frame " << f;
    }
    if (current.size() == 2) {
      ++frames_with_both;
      EXPECT_NE(current[0].track_id, current[1].track_id);
      if ((current[0].box & current[1].box).area() > 0) ++frames_overlapping;
    }
    previous = current;
    previous_flow = flow;
    cv::goodFeaturesToTrack(image.gray, previous_points, 600, 0.01, 6);
  }
  EXPECT_EQ(frames_with_both, 24);
  EXPECT_GE(frames_overlapping, 4) << "the two people must actually cross";
  EXPECT_EQ(tracker.IssuedIds(), 2);
}

TEST(ObjectIdTrackerTest, InheritsOnlyWithTheSameClassAndEnoughMatches) {
  ObjectIdTracker tracker(5);
  std::vector<Instance> previous = {Box(0, {10, 10, 30, 30}), Box(0, {100, 10, 30, 30})};
  std::vector<Instance> none;
  tracker.Assign(none, previous, {});
  EXPECT_EQ(previous[0].track_id, 0);
  EXPECT_EQ(previous[1].track_id, 1);

  // The first moves by 5 px with 8 shared tracks; the second changes class; a third is new.
  std::vector<Instance> current = {Box(0, {15, 10, 30, 30}), Box(2, {100, 10, 30, 30}),
                                   Box(0, {160, 50, 20, 20})};
  std::vector<FlowTrack> tracks = Shifted({10, 10, 30, 30}, {5, 0}, 8);
  const std::vector<FlowTrack> second = Shifted({100, 10, 30, 30}, {0, 0}, 8);
  tracks.insert(tracks.end(), second.begin(), second.end());
  const IdAssignment assignment = tracker.Assign(previous, current, tracks);
  EXPECT_EQ(current[0].track_id, 0);
  EXPECT_EQ(assignment.predecessor[0], 0);
  EXPECT_EQ(assignment.shared_tracks[0], 8);
  EXPECT_EQ(assignment.predecessor[1], -1);
  EXPECT_EQ(current[1].track_id, 2);
  EXPECT_EQ(current[2].track_id, 3);

  // Four shared tracks are too few.
  std::vector<Instance> next = {Box(0, {15, 10, 30, 30})};
  tracker.Assign(current, next, Shifted({15, 10, 30, 30}, {0, 0}, 4));
  EXPECT_EQ(next[0].track_id, 4);
}

TEST(ObjectIdTrackerTest, APredecessorWithoutIdSharesANewOne) {
  ObjectIdTracker tracker(3);
  std::vector<Instance> previous = {Box(0, {10, 10, 30, 30})};  // track_id -1
  std::vector<Instance> current = {Box(0, {10, 10, 30, 30})};
  tracker.Assign(previous, current, Shifted({10, 10, 30, 30}, {0, 0}, 5));
  EXPECT_EQ(previous[0].track_id, 0);
  EXPECT_EQ(current[0].track_id, 0);
}

TEST(ObjectIdTrackerTest, ASplitPassesTheIdToTheLargerPart) {
  ObjectIdTracker tracker(3);
  std::vector<Instance> previous = {Box(0, {10, 10, 80, 30})};
  std::vector<Instance> none;
  tracker.Assign(none, previous, {});
  std::vector<Instance> current = {Box(0, {10, 10, 30, 30}), Box(0, {50, 10, 40, 30})};
  std::vector<FlowTrack> tracks = Shifted({10, 10, 30, 30}, {0, 0}, 6);
  const std::vector<FlowTrack> more = Shifted({50, 10, 40, 30}, {0, 0}, 9);
  tracks.insert(tracks.end(), more.begin(), more.end());
  tracker.Assign(previous, current, tracks);
  EXPECT_EQ(current[1].track_id, previous[0].track_id);
  EXPECT_NE(current[0].track_id, previous[0].track_id);
}

TEST(ObjectIdTrackerTest, RejectsAZeroThreshold) { EXPECT_THROW(ObjectIdTracker(0), Error); }

// An object walks right 4 px a frame; the detector misses it on frames [gap_start, gap_end).
// Returns its track ID on every frame it was detected.
std::vector<int> IdsThroughAGap(ObjectIdTracker& tracker, int frames, int gap_start, int gap_end,
                                std::vector<int>* remembered = nullptr) {
  const cv::Size size(400, 100);
  std::vector<int> ids;
  std::vector<Instance> previous;
  for (int f = 0; f < frames; ++f) {
    const cv::Rect now(20 + 4 * f, 20, 40, 50);
    const cv::Rect before(20 + 4 * (f - 1), 20, 40, 50);
    // The tracks exist whether or not the detector saw the object: its features are tracked.
    const std::vector<FlowTrack> tracks =
        f > 0 ? Shifted(before, {4, 0}, 20) : std::vector<FlowTrack>();
    std::vector<Instance> current;
    if (f < gap_start || f >= gap_end) current.push_back(Box(0, now, size));
    const IdAssignment assignment = tracker.Assign(previous, current, tracks);
    for (std::size_t a = 0; a < current.size(); ++a) {
      ids.push_back(current[a].track_id);
      if (remembered != nullptr) remembered->push_back(assignment.remembered[a]);
    }
    previous = current;
  }
  return ids;
}

TEST(ObjectIdTrackerTest, KeepsItsIdThroughAThreeFrameDetectionGap) {
  ObjectIdTracker tracker(5, /*memory_frames=*/5);
  std::vector<int> remembered;
  const std::vector<int> ids = IdsThroughAGap(tracker, 10, 3, 6, &remembered);
  ASSERT_EQ(ids.size(), 7u);
  for (const int id : ids) EXPECT_EQ(id, ids.front());
  EXPECT_EQ(remembered[3], 3) << "frame 6 came back after 3 frames absent";
  EXPECT_EQ(tracker.IssuedIds(), 1);
  EXPECT_EQ(tracker.Remembered(), 0u);

  // Without memory the same sequence gives the object a new ID after the gap.
  ObjectIdTracker forgetful(5, 0);
  const std::vector<int> forgotten = IdsThroughAGap(forgetful, 10, 3, 6);
  EXPECT_NE(forgotten[3], forgotten[0]);
}

TEST(ObjectIdTrackerTest, AnObjectAbsentLongerThanTheMemoryExpires) {
  ObjectIdTracker tracker(5, /*memory_frames=*/3);
  // Absent 4 frames (3..6) with a 3-frame memory: a new ID.
  const std::vector<int> ids = IdsThroughAGap(tracker, 10, 3, 7);
  ASSERT_EQ(ids.size(), 6u);
  EXPECT_EQ(ids[2], ids[0]);
  EXPECT_NE(ids[3], ids[0]);
  EXPECT_EQ(tracker.IssuedIds(), 2);
  // Exactly as long as the memory: kept.
  ObjectIdTracker just(5, 3);
  const std::vector<int> kept = IdsThroughAGap(just, 10, 3, 6);
  EXPECT_EQ(kept[3], kept[0]);
}

TEST(ObjectIdTrackerTest, ARememberedObjectWithoutTracksIsForgotten) {
  // The object vanished for real (occluded, left): no tracks carry its mask, so an object
  // appearing where it was is someone new.
  ObjectIdTracker tracker(5, 5);
  const cv::Size size(400, 100);
  std::vector<Instance> previous = {Box(0, {20, 20, 40, 50}, size)};
  std::vector<Instance> none;
  tracker.Assign(none, previous, {});
  tracker.Assign(previous, none, {});
  EXPECT_EQ(tracker.Remembered(), 0u);
  std::vector<Instance> again = {Box(0, {20, 20, 40, 50}, size)};
  tracker.Assign(none, again, {});
  EXPECT_NE(again[0].track_id, previous[0].track_id);
}

TEST(ObjectIdTrackerTest, CarriedInstancesKeepTheirIdsWithoutSharedTracks) {
  ObjectIdTracker tracker(5);
  std::vector<Instance> previous = {Box(0, {10, 10, 30, 30}), Box(0, {100, 10, 30, 30})};
  std::vector<Instance> none;
  tracker.Assign(none, previous, {});
  // Carried masks come with their IDs; two tracks are below Dynamic.minIdMatches.
  std::vector<Instance> current = {Box(0, {102, 10, 30, 30}), Box(0, {12, 10, 30, 30})};
  current[0].track_id = previous[1].track_id;
  current[1].track_id = previous[0].track_id;
  const IdAssignment assignment =
      tracker.Assign(previous, current, Shifted({10, 10, 30, 30}, {2, 0}, 2));
  EXPECT_EQ(current[0].track_id, 1);
  EXPECT_EQ(current[1].track_id, 0);
  EXPECT_EQ(assignment.predecessor[0], 1);
  EXPECT_EQ(assignment.predecessor[1], 0);
  EXPECT_EQ(tracker.IssuedIds(), 2);
}

TEST(ObjectIdTrackerTest, RejectsBadMemorySettings) {
  EXPECT_THROW(ObjectIdTracker(5, -1), Error);
  EXPECT_THROW(ObjectIdTracker(5, 3, 0.0), Error);
  EXPECT_THROW(ObjectIdTracker(5, 3, 1.5), Error);
}

}  // namespace
}  // namespace drvslam
