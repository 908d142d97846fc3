#include "drvslam/loop/loop_corrector.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <vector>

namespace drvslam {
namespace {

// The keyframe whose pose change a map point follows: the one that moved it with the loop
// transform, else its reference keyframe, else any observer that has a change; -1 if none.
long Anchor(const MapPoint& point, const std::map<long, long>& moved_by,
            const std::map<long, std::pair<SE3, SE3>>& change) {
  const auto moved = moved_by.find(point.Id());
  if (moved != moved_by.end() && change.count(moved->second)) return moved->second;
  const auto reference = point.ReferenceKeyFrame();
  if (reference && change.count(reference->Id())) return reference->Id();
  for (const auto& [id, observation] : point.Observations()) {
    if (change.count(id)) return id;
  }
  return -1;
}

bool InMap(const Map& map, const std::shared_ptr<KeyFrame>& keyframe) {
  if (keyframe->IsBad()) return false;
  for (const auto& other : map.KeyFrames()) {
    if (other == keyframe) return true;
  }
  return false;
}

}  // namespace

LoopCorrectionStats CorrectLoop(const LoopMatch& match, Map& map, const OrbMatcher& matcher,
                                const LoopCorrectionRules& rules, KeyFrameEdgeSet* loop_edges) {
  LoopCorrectionStats stats;
  const auto& current = match.current;
  const ScalePyramid& pyramid = current->Geometry().pyramid;
  std::map<long, SE3> uncorrected;
  std::map<long, long> moved_by;  // map point id -> keyframe id that moved it
  KeyFrameEdgeSet new_edges;
  std::vector<std::shared_ptr<KeyFrame>> graph_keyframes;

  // Step 1, under the update lock: the loop is closed locally (the current neighbourhood moved
  // onto the loop side, duplicates fused, loop edges found).
  {
    std::lock_guard<std::mutex> lock(map.UpdateMutex());
    if (!InMap(map, current) || !InMap(map, match.loop)) return stats;
    stats.applied = true;
    current->UpdateConnections();

    // The current keyframe's neighbourhood moves rigidly with it.
    std::vector<std::shared_ptr<KeyFrame>> group{current};
    std::set<long> group_ids{current->Id()};
    for (const auto& neighbour : current->CovisiblesByWeight()) {
      if (!neighbour->IsBad() && group_ids.insert(neighbour->Id()).second) {
        group.push_back(neighbour);
      }
    }
    // Keyframes made after the current one (threaded: still queued for local mapping, so not
    // yet connected) were tracked in its neighbourhood: they move with it too, without fusion.
    std::vector<std::shared_ptr<KeyFrame>> followers;
    const auto all_keyframes = map.KeyFrames();
    for (const auto& keyframe : all_keyframes) {
      if (keyframe->Id() > current->Id() && !keyframe->IsBad() &&
          !group_ids.count(keyframe->Id())) {
        followers.push_back(keyframe);
      }
    }
    const SE3 T_wc_old = current->InversePose();
    std::map<long, SE3> corrected;
    std::vector<std::shared_ptr<KeyFrame>> moved = group;
    moved.insert(moved.end(), followers.begin(), followers.end());
    for (const auto& keyframe : moved) {
      uncorrected[keyframe->Id()] = keyframe->Pose();
      corrected[keyframe->Id()] = keyframe->Pose() * T_wc_old * match.corrected_T_cw;
    }
    for (const auto& keyframe : moved) {
      const SE3 T_old = uncorrected[keyframe->Id()];
      const SE3 T_new_inverse = corrected[keyframe->Id()].Inverse();
      for (const auto& point : keyframe->MapPoints()) {
        if (!point || point->IsBad() || moved_by.count(point->Id())) continue;
        point->SetPosition(T_new_inverse * (T_old * point->Position()));
        moved_by[point->Id()] = keyframe->Id();
      }
    }
    for (const auto& keyframe : moved) keyframe->SetPose(corrected[keyframe->Id()]);
    stats.corrected_keyframes = static_cast<int>(moved.size());
    stats.corrected_points = static_cast<int>(moved_by.size());

    // Neighbours before fusion, to tell the links the loop creates.
    std::map<long, std::set<long>> previous;
    for (const auto& keyframe : group) {
      auto& ids = previous[keyframe->Id()];
      ids = group_ids;
      for (const auto& neighbour : keyframe->CovisiblesByWeight()) ids.insert(neighbour->Id());
    }

    // The loop's matched points take the place of their duplicates on the current side.
    std::vector<std::shared_ptr<MapPoint>> replaced;
    for (std::size_t i = 0; i < match.matched_points.size(); ++i) {
      const auto& loop_point = match.matched_points[i];
      if (!loop_point || loop_point->IsBad()) continue;
      const auto existing = current->MapPointAt(i);
      if (existing == loop_point) continue;
      if (existing && !existing->IsBad()) {
        existing->Replace(loop_point);
        replaced.push_back(existing);
      } else if (loop_point->IndexIn(current->Id()) < 0) {
        if (!loop_point->AddObservation(current, static_cast<int>(i))) continue;  // culled
        current->AddMapPoint(loop_point, i);
        loop_point->ComputeDistinctiveDescriptor();
      } else {
        continue;
      }
      ++stats.fused_points;
    }
    // The loop neighbourhood's points into every moved keyframe.
    std::vector<std::shared_ptr<MapPoint>> loop_points;
    std::set<long> seen;
    std::vector<std::shared_ptr<KeyFrame>> loop_side{match.loop};
    for (const auto& neighbour : match.loop->CovisiblesByWeight()) loop_side.push_back(neighbour);
    for (const auto& keyframe : loop_side) {
      if (keyframe->IsBad() || group_ids.count(keyframe->Id())) continue;
      for (const auto& point : keyframe->MapPoints()) {
        if (point && !point->IsBad() && seen.insert(point->Id()).second) {
          loop_points.push_back(point);
        }
      }
    }
    for (const auto& keyframe : group) {
      stats.fused_points +=
          matcher.Fuse(keyframe, loop_points, rules.fuse_radius_factor, &replaced);
    }
    for (const auto& point : replaced) map.EraseMapPoint(point->Id());
    for (const auto& point : current->MapPoints()) {
      if (point && !point->IsBad()) point->UpdateNormalAndDepth(pyramid);
    }

    // Links that did not exist before are the loop edges.
    new_edges.insert(std::minmax(current->Id(), match.loop->Id()));
    for (const auto& keyframe : group) {
      keyframe->UpdateConnections();
      const auto& before = previous[keyframe->Id()];
      for (const auto& neighbour : keyframe->CovisiblesByWeight()) {
        if (!before.count(neighbour->Id())) {
          new_edges.insert(std::minmax(keyframe->Id(), neighbour->Id()));
        }
      }
    }
    stats.new_loop_edges = static_cast<int>(new_edges.size());
    // Followers not yet in the spanning tree have no edge in the graph: they follow the current
    // keyframe in step 3 instead.
    for (const auto& keyframe : all_keyframes) {
      if (keyframe->Id() > current->Id() && !keyframe->Parent()) continue;
      graph_keyframes.push_back(keyframe);
    }
    map.RaiseCorrectionEpoch();
  }

  // Step 2, without the lock (tracking goes on in the locally corrected map): the essential
  // graph is optimized. Local mapping is paused and global bundle adjustment stopped by the
  // caller, so the graph's keyframes and links stay as they are.
  EssentialGraphInput input;
  input.keyframes = std::move(graph_keyframes);
  input.uncorrected_T_cw = uncorrected;
  input.loop_edges = *loop_edges;
  input.new_loop_edges = new_edges;
  input.min_covisibility_weight = rules.min_covisibility_weight;
  input.fixed_keyframe_id = match.loop->Id();
  const EssentialGraph graph = BuildEssentialGraph(input);
  PoseGraphOptions options;
  options.max_iterations = rules.pose_graph_iterations;
  const PoseGraphResult result = OptimizePoseGraph(graph.problem, options);
  stats.graph_keyframes = static_cast<int>(graph.keyframes.size());
  stats.graph_edges = static_cast<int>(graph.problem.edges.size());
  stats.graph_iterations = result.iterations;
  stats.graph_initial_cost = result.initial_cost;
  stats.graph_final_cost = result.final_cost;
  loop_edges->insert(new_edges.begin(), new_edges.end());

  // Step 3, under the lock: every keyframe takes its optimized pose and every point follows its
  // keyframe from the graph's initial estimate to its optimum.
  std::vector<std::shared_ptr<MapPoint>> points;
  {
    std::lock_guard<std::mutex> lock(map.UpdateMutex());
    if (!InMap(map, current)) return stats;      // the map was reset meanwhile
    std::map<long, std::pair<SE3, SE3>> change;  // keyframe id -> (before, after)
    std::map<long, std::shared_ptr<KeyFrame>> by_id;
    for (std::size_t i = 0; i < graph.keyframes.size(); ++i) {
      change[graph.keyframes[i]->Id()] = {graph.problem.poses_cw[i], result.poses_cw[i]};
      by_id[graph.keyframes[i]->Id()] = graph.keyframes[i];
    }
    // Keyframes outside the graph (made by tracking since step 1, or still unconnected) were
    // made next to the current keyframe: they keep their pose relative to it.
    const auto current_change = change.find(current->Id());
    for (const auto& keyframe : map.KeyFrames()) {
      if (keyframe->IsBad() || change.count(keyframe->Id()) || current_change == change.end()) {
        continue;
      }
      const auto& [current_before, current_after] = current_change->second;
      const SE3 before = keyframe->Pose();
      change[keyframe->Id()] = {before, before * current_before.Inverse() * current_after};
      by_id[keyframe->Id()] = keyframe;
    }
    points = map.MapPoints();
    for (const auto& point : points) {
      if (point->IsBad()) continue;
      const long anchor = Anchor(*point, moved_by, change);
      if (anchor < 0) continue;
      const auto& [before, after] = change[anchor];
      point->SetPosition(after.Inverse() * (before * point->Position()));
    }
    for (const auto& [id, poses] : change) by_id[id]->SetPose(poses.second);
    map.RaiseCorrectionEpoch();
  }
  // Viewing directions and distance ranges follow outside the lock (mapping is still paused).
  for (const auto& point : points) {
    if (!point->IsBad()) point->UpdateNormalAndDepth(pyramid);
  }
  return stats;
}

}  // namespace drvslam
