// The route graph the synthetic actors walk: lanes, side columns, exits and seats laid out
// around the table of a RoomLayout. Kept apart from the walking simulation (actors.cc), which
// only picks the next node.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drvslam/tools/synth/room_layout.h"

namespace drvslam::synth::routes {

// kPass: a lane node nobody stops at.
enum class NodeKind { kLane, kPass, kExit, kApproach, kSeat };

struct Node {
  Eigen::Vector2d p;
  NodeKind kind;
  int stool = -1;    // for kApproach and kSeat
  int partner = -1;  // kApproach <-> kSeat
};

// The routes walkers take: a front lane between the camera and the table, a back lane between
// the table and the back shelves, two side columns joining them out of the standard view, exits
// at both ends of both lanes (out of view), and a seat behind each stool.
struct RouteGraph {
  std::vector<Node> nodes;
  std::vector<std::vector<int>> next;

  int Add(const Eigen::Vector2d& p, NodeKind kind) {
    nodes.push_back({p, kind});
    next.emplace_back();
    return static_cast<int>(nodes.size()) - 1;
  }
  void Link(int a, int b) {
    next[a].push_back(b);
    next[b].push_back(a);
  }
};

// The graph for `layout`: lanes and exits from its table and walls, a seat at each stool.
RouteGraph BuildRoutes(const RoomLayout& layout);

}  // namespace drvslam::synth::routes
