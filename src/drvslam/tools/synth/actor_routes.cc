#include "drvslam/tools/synth/actor_routes.h"

#include <algorithm>
#include <utility>

namespace drvslam::synth::routes {

RouteGraph BuildRoutes(const RoomLayout& layout) {
  RouteGraph graph;
  const double front_y = -1.15;
  const double back_y = std::min(1.35, layout.max.y() - layout.shelf_depth - 0.4);
  const double side_x = 0.5 * layout.table_size.x() + 0.45;
  const double exit_left = layout.min.x() + 0.45;
  const double exit_right = layout.max.x() - 0.45;

  const int front_exit_l = graph.Add({exit_left, front_y}, NodeKind::kExit);
  const int front_l = graph.Add({-side_x, front_y}, NodeKind::kLane);
  const int front_cl = graph.Add({-0.45, front_y}, NodeKind::kLane);
  const int front_cr = graph.Add({0.45, front_y}, NodeKind::kLane);
  const int front_r = graph.Add({side_x, front_y}, NodeKind::kLane);
  const int front_exit_r = graph.Add({exit_right, front_y}, NodeKind::kExit);
  graph.Link(front_exit_l, front_l);
  graph.Link(front_l, front_cl);
  graph.Link(front_cl, front_cr);
  graph.Link(front_cr, front_r);
  graph.Link(front_r, front_exit_r);
  // A step towards the camera between the two central front nodes: people passing this close
  // cover about half of the image, as they do at times in the real walking sequences.
  const int close = graph.Add({0.0, front_y - 0.2}, NodeKind::kPass);
  graph.Link(front_cl, close);
  graph.Link(close, front_cr);

  // Back lane, left to right, with an approach point behind each stool.
  std::vector<std::pair<double, int>> back;
  const int back_exit_l = graph.Add({exit_left, back_y}, NodeKind::kExit);
  const int back_l = graph.Add({-side_x, back_y}, NodeKind::kLane);
  const int back_r = graph.Add({side_x, back_y}, NodeKind::kLane);
  const int back_exit_r = graph.Add({exit_right, back_y}, NodeKind::kExit);
  back.push_back({exit_left, back_exit_l});
  back.push_back({-side_x, back_l});
  back.push_back({side_x, back_r});
  back.push_back({exit_right, back_exit_r});
  for (int s = 0; s < static_cast<int>(layout.stools.size()); ++s) {
    const Eigen::Vector2d& stool = layout.stools[s];
    const int approach = graph.Add({stool.x(), back_y}, NodeKind::kApproach);
    const int seat = graph.Add(stool, NodeKind::kSeat);
    graph.nodes[approach].stool = graph.nodes[seat].stool = s;
    graph.nodes[approach].partner = seat;
    graph.nodes[seat].partner = approach;
    graph.Link(approach, seat);
    back.push_back({stool.x(), approach});
  }
  std::sort(back.begin(), back.end());
  for (std::size_t k = 1; k < back.size(); ++k) graph.Link(back[k - 1].second, back[k].second);
  graph.Link(front_l, back_l);
  graph.Link(front_r, back_r);
  return graph;
}

}  // namespace drvslam::synth::routes
