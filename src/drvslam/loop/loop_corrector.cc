#include "drvslam/loop/loop_corrector.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <vector>

namespace drvslam {
namespace {

// The keyframe whose pose a map point follows: the one that moved it with the loop
// transform, else its reference keyframe, else any observer in the graph.
std::shared_ptr<KeyFrame> Anchor(const MapPoint& point, const std::map<long, long>& moved_by,
                                 const std::map<long, std::shared_ptr<KeyFrame>>& graph_keyframes) {
  const auto find = [&](long id) -> std::shared_ptr<KeyFrame> {
    const auto it = graph_keyframes.find(id);
    return it == graph_keyframes.end() ? nullptr : it->second;
  };
  const auto moved = moved_by.find(point.Id());
  if (moved != moved_by.end()) {
    if (auto keyframe = find(moved->second)) return keyframe;
  }
  const auto reference = point.ReferenceKeyFrame();
  if (reference) {
    if (auto keyframe = find(reference->Id())) return keyframe;
  }
  for (const auto& [id, observation] : point.Observations()) {
    if (auto keyframe = find(id)) return keyframe;
  }
  return nullptr;
}

}  // namespace

LoopCorrectionStats CorrectLoop(const LoopMatch& match, Map& map, const OrbMatcher& matcher,
                                const LoopCorrectionRules& rules, KeyFrameEdgeSet* loop_edges) {
  LoopCorrectionStats stats;
  const auto& current = match.current;
  const ScalePyramid& pyramid = current->Geometry().pyramid;
  std::lock_guard<std::mutex> lock(map.UpdateMutex());
  const auto in_map = [&map](const std::shared_ptr<KeyFrame>& keyframe) {
    if (keyframe->IsBad()) return false;
    for (const auto& other : map.KeyFrames()) {
      if (other == keyframe) return true;
    }
    return false;
  };
  if (!in_map(current) || !in_map(match.loop)) return stats;
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
  const SE3 T_wc_old = current->InversePose();
  std::map<long, SE3> uncorrected;
  std::map<long, SE3> corrected;
  for (const auto& keyframe : group) {
    uncorrected[keyframe->Id()] = keyframe->Pose();
    corrected[keyframe->Id()] = keyframe->Pose() * T_wc_old * match.corrected_T_cw;
  }
  std::map<long, long> moved_by;  // map point id -> keyframe id that moved it
  for (const auto& keyframe : group) {
    const SE3 T_old = uncorrected[keyframe->Id()];
    const SE3 T_new_inverse = corrected[keyframe->Id()].Inverse();
    for (const auto& point : keyframe->MapPoints()) {
      if (!point || point->IsBad() || moved_by.count(point->Id())) continue;
      point->SetPosition(T_new_inverse * (T_old * point->Position()));
      moved_by[point->Id()] = keyframe->Id();
    }
  }
  for (const auto& keyframe : group) keyframe->SetPose(corrected[keyframe->Id()]);
  stats.corrected_keyframes = static_cast<int>(group.size());
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
      if (!loop_point->AddObservation(current, static_cast<int>(i))) continue;  // culled meanwhile
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
    stats.fused_points += matcher.Fuse(keyframe, loop_points, rules.fuse_radius_factor, &replaced);
  }
  for (const auto& point : replaced) map.EraseMapPoint(point->Id());
  for (const auto& point : current->MapPoints()) {
    if (point && !point->IsBad()) point->UpdateNormalAndDepth(pyramid);
  }

  // Links that did not exist before are the loop edges.
  KeyFrameEdgeSet new_edges;
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

  EssentialGraphInput input;
  input.keyframes = map.KeyFrames();
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

  // Every point follows its keyframe from the graph's initial estimate to its optimum.
  std::map<long, std::shared_ptr<KeyFrame>> graph_keyframes;
  std::map<long, std::pair<SE3, SE3>> change;  // keyframe id -> (before, after)
  for (std::size_t i = 0; i < graph.keyframes.size(); ++i) {
    graph_keyframes[graph.keyframes[i]->Id()] = graph.keyframes[i];
    change[graph.keyframes[i]->Id()] = {graph.problem.poses_cw[i], result.poses_cw[i]};
  }
  for (const auto& point : map.MapPoints()) {
    if (point->IsBad()) continue;
    const auto anchor = Anchor(*point, moved_by, graph_keyframes);
    if (!anchor) continue;
    const auto& [before, after] = change[anchor->Id()];
    point->SetPosition(after.Inverse() * (before * point->Position()));
    point->UpdateNormalAndDepth(pyramid);
  }
  for (std::size_t i = 0; i < graph.keyframes.size(); ++i) {
    graph.keyframes[i]->SetPose(result.poses_cw[i]);
  }
  loop_edges->insert(new_edges.begin(), new_edges.end());
  return stats;
}

}  // namespace drvslam
