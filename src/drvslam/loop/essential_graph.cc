#include "drvslam/loop/essential_graph.h"

#include <algorithm>

namespace drvslam {

EssentialGraph BuildEssentialGraph(const EssentialGraphInput& input) {
  EssentialGraph graph;
  std::map<long, int> index;
  for (const auto& keyframe : input.keyframes) {
    if (!keyframe || keyframe->IsBad() || index.count(keyframe->Id())) continue;
    index[keyframe->Id()] = static_cast<int>(graph.keyframes.size());
    graph.keyframes.push_back(keyframe);
    graph.problem.poses_cw.push_back(keyframe->Pose());
    graph.problem.fixed.push_back(keyframe->Id() == input.fixed_keyframe_id);
  }
  const auto uncorrected = [&](int i) {
    const auto it = input.uncorrected_T_cw.find(graph.keyframes[i]->Id());
    return it != input.uncorrected_T_cw.end() ? it->second : graph.problem.poses_cw[i];
  };
  KeyFrameEdgeSet added;
  // measured_after: the relative pose across the corrected poses (new loop edges).
  const auto add_edge = [&](long a, long b, bool measured_after) {
    if (a == b) return false;
    const auto key = std::minmax(a, b);
    if (added.count(key)) return false;
    const auto ia = index.find(key.first);
    const auto ib = index.find(key.second);
    if (ia == index.end() || ib == index.end()) return false;
    added.insert(key);
    PoseGraphEdge edge;
    edge.from = ia->second;
    edge.to = ib->second;
    const SE3 T_from = measured_after ? graph.problem.poses_cw[edge.from] : uncorrected(edge.from);
    const SE3 T_to = measured_after ? graph.problem.poses_cw[edge.to] : uncorrected(edge.to);
    edge.T_to_from = T_to * T_from.Inverse();
    graph.problem.edges.push_back(edge);
    return true;
  };

  for (const auto& [a, b] : input.new_loop_edges) graph.loop_edges += add_edge(a, b, true);
  for (const auto& [a, b] : input.loop_edges) graph.loop_edges += add_edge(a, b, false);
  for (const auto& keyframe : graph.keyframes) {
    const auto parent = keyframe->Parent();
    if (parent) graph.tree_edges += add_edge(keyframe->Id(), parent->Id(), false);
  }
  for (const auto& keyframe : graph.keyframes) {
    for (const auto& neighbour : keyframe->CovisiblesByWeight()) {
      if (keyframe->Weight(neighbour->Id()) < input.min_covisibility_weight) break;
      graph.covisibility_edges += add_edge(keyframe->Id(), neighbour->Id(), false);
    }
  }
  return graph;
}

}  // namespace drvslam
