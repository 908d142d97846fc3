// From a live map to MapFileContents and back: which keyframes and points a map file keeps
// (those not removed), and how they are rebuilt into a Map with the same graph.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "drvslam/map/frame_features.h"
#include "drvslam/map/map.h"
#include "drvslam/mapfile/map_file.h"

namespace drvslam {

// Fills contents.keyframes, contents.points and the id counters from the map's live keyframes
// and points. The caller holds map.UpdateMutex(), so no pose moves while they are read.
void CaptureMap(Map& map, MapFileContents* contents);

// Builds the saved keyframes and points into `map` (expected empty), with their observations,
// covisibility edges and spanning tree, on `geometry` (the run's camera and ORB pyramid, which
// CheckMapCompatibility accepted). `attach_bow` gives each keyframe its bag of words. Point
// descriptors, viewing directions and distance ranges are recomputed from the observations, as
// local mapping computes them. Returns the keyframes by id. Throws Error naming `path` when
// the contents cannot make a map.
std::map<long, std::shared_ptr<KeyFrame>> RestoreMap(
    const MapFileContents& contents, const std::shared_ptr<const SensorGeometry>& geometry,
    const std::function<void(KeyFrame&)>& attach_bow, Map* map, const std::string& path);

}  // namespace drvslam
