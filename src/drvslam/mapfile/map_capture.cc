#include "drvslam/mapfile/map_capture.h"

#include <algorithm>
#include <set>

#include "drvslam/core/error.h"

namespace drvslam {

void CaptureMap(Map& map, MapFileContents* contents) {
  long max_keyframe_id = -1;
  long max_point_id = -1;
  // Mapping may add keyframes meanwhile: every reference is kept only to a captured keyframe.
  std::vector<std::shared_ptr<KeyFrame>> captured;
  std::set<long> ids;
  for (const auto& keyframe : map.KeyFrames()) {
    if (keyframe->IsBad()) continue;
    captured.push_back(keyframe);
    ids.insert(keyframe->Id());
  }
  for (const auto& keyframe : captured) {
    KeyFrameRecord record;
    record.id = keyframe->Id();
    record.frame_id = keyframe->FrameId();
    record.timestamp = keyframe->Timestamp();
    record.T_cw = keyframe->Pose();
    const FrameFeatures& features = keyframe->Features();
    record.keypoints = features.KeypointsForMapFile();
    record.descriptors = features.Descriptors();
    record.depth.resize(features.Size());
    for (std::size_t i = 0; i < features.Size(); ++i) {
      record.depth[i] = std::max(0.f, features.Depth(i));
    }
    for (const auto& neighbour : keyframe->CovisiblesByWeight()) {
      const int weight = keyframe->Weight(neighbour->Id());
      if (!ids.count(neighbour->Id()) || weight <= 0) continue;
      record.connections.emplace_back(neighbour->Id(), weight);
    }
    const auto parent = keyframe->Parent();
    record.parent_id = parent && ids.count(parent->Id()) ? parent->Id() : -1;
    max_keyframe_id = std::max(max_keyframe_id, record.id);
    contents->keyframes.push_back(std::move(record));
  }
  for (const auto& point : map.MapPoints()) {
    if (point->IsBad()) continue;
    MapPointRecord record;
    record.id = point->Id();
    record.position = point->Position();
    record.visible = point->Visible();
    record.found = point->Found();
    for (const auto& [keyframe_id, observation] : point->Observations()) {
      if (!ids.count(keyframe_id)) continue;
      record.observations.emplace_back(keyframe_id, observation.index);
    }
    if (record.observations.empty()) continue;
    const auto reference = point->ReferenceKeyFrame();
    record.reference_keyframe_id = reference && ids.count(reference->Id())
                                       ? reference->Id()
                                       : record.observations.front().first;
    max_point_id = std::max(max_point_id, record.id);
    contents->points.push_back(std::move(record));
  }
  contents->next_keyframe_id = max_keyframe_id + 1;
  contents->next_map_point_id = max_point_id + 1;
}

std::map<long, std::shared_ptr<KeyFrame>> RestoreMap(
    const MapFileContents& contents, const std::shared_ptr<const SensorGeometry>& geometry,
    const std::function<void(KeyFrame&)>& attach_bow, Map* map, const std::string& path) {
  std::map<long, std::shared_ptr<KeyFrame>> keyframes;
  for (const KeyFrameRecord& record : contents.keyframes) {
    std::shared_ptr<const FrameFeatures> features;
    try {
      features = std::make_shared<const FrameFeatures>(geometry, record.keypoints,
                                                       record.descriptors, record.depth);
    } catch (const Error& error) {
      throw Error(path + ": keyframe " + std::to_string(record.id) + ": " + error.what());
    }
    auto keyframe = std::make_shared<KeyFrame>(record.id, record.frame_id, record.timestamp,
                                               std::move(features), record.T_cw,
                                               std::vector<std::shared_ptr<MapPoint>>());
    attach_bow(*keyframe);
    keyframes.emplace(record.id, std::move(keyframe));
  }
  std::vector<std::shared_ptr<MapPoint>> points;
  points.reserve(contents.points.size());
  for (const MapPointRecord& record : contents.points) {
    auto point = std::make_shared<MapPoint>(record.id, record.position,
                                            keyframes.at(record.reference_keyframe_id));
    for (const auto& [keyframe_id, index] : record.observations) {
      const auto& keyframe = keyframes.at(keyframe_id);
      // One point per keypoint: a slot already taken keeps its first point.
      if (keyframe->MapPointAt(static_cast<std::size_t>(index))) continue;
      keyframe->AddMapPoint(point, static_cast<std::size_t>(index));
      point->AddObservation(keyframe, index);
    }
    if (point->ObservationCount() == 0) continue;
    point->IncreaseVisible(std::max(0, record.visible - point->Visible()));
    point->IncreaseFound(std::max(0, record.found - point->Found()));
    points.push_back(std::move(point));
  }
  for (const KeyFrameRecord& record : contents.keyframes) {
    std::vector<std::pair<std::shared_ptr<KeyFrame>, int>> edges;
    for (const auto& [id, weight] : record.connections)
      edges.emplace_back(keyframes.at(id), weight);
    const std::shared_ptr<KeyFrame> parent =
        record.parent_id >= 0 ? keyframes.at(record.parent_id) : nullptr;
    keyframes.at(record.id)->RestoreConnections(edges, parent);
  }
  for (const auto& point : points) {
    point->ComputeDistinctiveDescriptor();
    point->UpdateNormalAndDepth(geometry->pyramid);
  }
  for (const auto& [id, keyframe] : keyframes) map->AddKeyFrame(keyframe);
  for (const auto& point : points) map->AddMapPoint(point);
  map->AdvanceIds(contents.next_keyframe_id, contents.next_map_point_id);
  return keyframes;
}

}  // namespace drvslam
