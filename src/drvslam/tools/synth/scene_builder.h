// Scene builder: the furnished room every scenario shares - textured walls, floor and ceiling,
// a table, stools, shelves full of boxes, and the static key objects on the table (books, a
// laptop, a keyboard, a mouse, a cup, a bottle), each key object an instance with its COCO
// class. Depends only on the layout and the seed, never on the actors or the scenario, so a
// dynamic scenario and its static counterpart show the same room.
#pragma once

#include <cstdint>
#include <vector>

#include "drvslam/tools/synth/instances_file.h"
#include "drvslam/tools/synth/room_layout.h"
#include "drvslam/tools/synth/scene.h"
#include "drvslam/tools/synth/texture_bank.h"

namespace drvslam::synth {

// Static key objects get ids from here on; actors take 1, 2, ... below it.
inline constexpr int kFirstObjectInstanceId = 100;

struct StaticScene {
  TriangleList triangles;  // world frame
  std::vector<SynthInstance> instances;
};

// Builds the room's geometry, queueing its textures in `bank`.
StaticScene BuildStaticScene(const RoomLayout& layout, uint64_t seed, TextureBank* bank);

}  // namespace drvslam::synth
