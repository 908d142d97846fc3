// Place-recognition costs on the tracking and loop paths: loading the default vocabulary
// (binary), the bag of words of one keyframe (1000 ORB features, with the direct index), keyframe
// database insertion and queries as the database grows, BoW matching against brute-force
// matching of a keyframe with a frame, and one whole relocalization against the map of a
// synthetic run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/feature/orb_extractor.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/keyframe_database.h"
#include "drvslam/loop/relocalizer.h"
#include "drvslam/loop/vocabulary_io.h"
#include "drvslam/map/map.h"
#include "drvslam/match/bow_matcher.h"
#include "drvslam/match/orb_matcher.h"
#include "drvslam/optim/pose_optimizer.h"
#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "drvslam/tools/vocab/training_images.h"
#include "drvslam/tracking/frame_factory.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam {
namespace {

const BowVocabulary* Vocabulary() {
  static const std::unique_ptr<BowVocabulary> vocabulary = [] {
    const std::string path = DefaultVocabularyPath();
    return path.empty() ? nullptr : std::make_unique<BowVocabulary>(LoadVocabulary(path));
  }();
  return vocabulary.get();
}

std::shared_ptr<const SensorGeometry> Geometry() {
  static const auto geometry =
      std::make_shared<const SensorGeometry>(CameraOptions{}, ScalePyramid(8, 1.2), 3.0);
  return geometry;
}

// ORB features (1000) of every opencv-doc photograph and every 10th frame of its videos, at
// 640x480: distinct places for the database.
const std::vector<std::shared_ptr<const FrameFeatures>>& PlaceFeatures() {
  static const std::vector<std::shared_ptr<const FrameFeatures>> features = [] {
    std::vector<std::shared_ptr<const FrameFeatures>> result;
    std::vector<std::string> inputs = {DRVSLAM_OPENCV_DATA_DIR};
    for (const char* video : {"vtest.avi", "Megamind.avi"}) {
      inputs.push_back(std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + video);
    }
    TrainingImageOptions options;
    OrbExtractor extractor{OrbExtractorOptions{}};
    try {
      ForEachTrainingImage(ListTrainingImages(inputs, options), options,
                           [&](std::size_t, const TrainingImageSource&, const cv::Mat& gray) {
                             cv::Mat image;
                             cv::resize(gray, image, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
                             std::vector<cv::KeyPoint> keypoints;
                             cv::Mat descriptors;
                             extractor.Extract(image, cv::Mat(), 1000, &keypoints, &descriptors);
                             if (keypoints.size() < 100) return;
                             result.push_back(std::make_shared<const FrameFeatures>(
                                 Geometry(), keypoints, descriptors, cv::Mat()));
                           });
    } catch (const std::exception&) {
      // Missing opencv-doc data: the benchmarks that need it report an error.
    }
    return result;
  }();
  return features;
}

struct PlaceBow {
  BowVector bow;
  FeatureVector features;
};

const std::vector<PlaceBow>& PlaceBows() {
  static const std::vector<PlaceBow> bows = [] {
    std::vector<PlaceBow> result;
    for (const auto& features : PlaceFeatures()) {
      PlaceBow place;
      Vocabulary()->Transform(features->Descriptors(), &place.bow, &place.features,
                              DirectIndexLevel(*Vocabulary()));
      result.push_back(std::move(place));
    }
    return result;
  }();
  return bows;
}

// n keyframes cycling through the places, each covisible with its 5 predecessors (a trajectory).
std::vector<std::shared_ptr<KeyFrame>> MakeKeyFrames(int n) {
  const auto& features = PlaceFeatures();
  const auto& bows = PlaceBows();
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  for (int i = 0; i < n; ++i) {
    const std::size_t place = static_cast<std::size_t>(i) % features.size();
    auto keyframe = std::make_shared<KeyFrame>(i, i, i, features[place], SE3::Identity(),
                                               std::vector<std::shared_ptr<MapPoint>>());
    keyframe->SetBow(bows[place].bow, bows[place].features);
    for (int j = std::max(0, i - 5); j < i; ++j) {
      keyframe->AddConnection(keyframes[j], 50 + i - j);
      keyframes[j]->AddConnection(keyframe, 50 + i - j);
    }
    keyframes.push_back(keyframe);
  }
  return keyframes;
}

bool Ready(benchmark::State& state) {
  if (Vocabulary() == nullptr) {
    state.SkipWithError("no default vocabulary was built");
    return false;
  }
  if (PlaceFeatures().size() < 10) {
    state.SkipWithError("opencv-doc images missing");
    return false;
  }
  return true;
}

void BM_LoadDefaultVocabulary(benchmark::State& state) {
  const std::string path = DefaultVocabularyPath();
  if (path.empty()) {
    state.SkipWithError("no default vocabulary was built");
    return;
  }
  for (auto _ : state) {
    BowVocabulary vocabulary = LoadVocabulary(path);
    benchmark::DoNotOptimize(vocabulary.WordCount());
  }
}
BENCHMARK(BM_LoadDefaultVocabulary)->Unit(benchmark::kMillisecond);

void BM_KeyFrameBow(benchmark::State& state) {
  if (!Ready(state)) return;
  const auto& features = *PlaceFeatures()[state.range(0) % PlaceFeatures().size()];
  const int level = DirectIndexLevel(*Vocabulary());
  BowVector bow;
  FeatureVector direct;
  for (auto _ : state) {
    Vocabulary()->Transform(features.Descriptors(), &bow, &direct, level);
    benchmark::DoNotOptimize(bow);
  }
  state.SetLabel(std::to_string(features.Size()) + " features, " + std::to_string(bow.size()) +
                 " words");
}
BENCHMARK(BM_KeyFrameBow)->Arg(0)->Arg(7)->Unit(benchmark::kMicrosecond);

void BM_DatabaseAdd(benchmark::State& state) {
  if (!Ready(state)) return;
  const auto keyframes = MakeKeyFrames(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    KeyFrameDatabase database;
    for (const auto& keyframe : keyframes) database.Add(keyframe);
    benchmark::DoNotOptimize(database.Size());
  }
  state.SetItemsProcessed(state.iterations() * keyframes.size());
  state.counters["us_per_keyframe"] = benchmark::Counter(
      static_cast<double>(keyframes.size()) / 1e6,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DatabaseAdd)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

// A query by a place's bag of words against n keyframes (every place appears n / places times).
void BM_RelocalizationQuery(benchmark::State& state) {
  if (!Ready(state)) return;
  const auto keyframes = MakeKeyFrames(static_cast<int>(state.range(0)));
  KeyFrameDatabase database;
  for (const auto& keyframe : keyframes) database.Add(keyframe);
  const BowVector& query = PlaceBows()[3].bow;
  std::size_t candidates = 0;
  for (auto _ : state) {
    candidates = database.RelocalizationCandidates(query).size();
    benchmark::DoNotOptimize(candidates);
  }
  state.SetLabel(std::to_string(keyframes.size()) + " keyframes (" +
                 std::to_string(PlaceBows().size()) + " places), " + std::to_string(candidates) +
                 " candidates");
}
BENCHMARK(BM_RelocalizationQuery)->Arg(100)->Arg(500)->Arg(2000)->Unit(benchmark::kMicrosecond);

void BM_LoopQuery(benchmark::State& state) {
  if (!Ready(state)) return;
  const auto keyframes = MakeKeyFrames(static_cast<int>(state.range(0)));
  KeyFrameDatabase database;
  for (const auto& keyframe : keyframes) database.Add(keyframe);
  const auto& keyframe = keyframes.back();
  std::size_t candidates = 0;
  for (auto _ : state) {
    candidates = database.LoopCandidates(keyframe, 0.0).size();
    benchmark::DoNotOptimize(candidates);
  }
  state.SetLabel(std::to_string(keyframes.size()) + " keyframes, " + std::to_string(candidates) +
                 " candidates");
}
BENCHMARK(BM_LoopQuery)->Arg(100)->Arg(500)->Arg(2000)->Unit(benchmark::kMicrosecond);

// A synthetic run (sequential) whose map the matching and relocalization benchmarks use.
struct SyntheticRun {
  std::unique_ptr<System> system;
  std::unique_ptr<FrameFactory> factory;
  std::vector<cv::Mat> bgr, depth;
  std::vector<double> stamps;
};

SyntheticRun& Run() {
  static SyntheticRun run = [] {
    SyntheticRun r;
    synth::SynthOptions options;
    options.scenario = "static_rpy";
    options.frames = 40;
    options.seed = 3;
    const synth::SynthSequence sequence(options);
    const Settings settings = sequence.MakeSettings();
    SystemOptions system_options;
    system_options.sequential = true;
    r.system = std::make_unique<System>(settings, TrackerOptions{}, system_options);
    r.factory = std::make_unique<FrameFactory>(settings);
    for (int i = 0; i < sequence.FrameCount(); ++i) {
      const synth::RenderBuffers buffers = sequence.Render(i);
      r.bgr.push_back(buffers.bgr);
      r.depth.push_back(buffers.depth);
      r.stamps.push_back(sequence.Stamp(i));
      r.system->TrackRGBD(buffers.bgr, buffers.depth, sequence.Stamp(i));
    }
    r.system->Shutdown();
    return r;
  }();
  return run;
}

// Brute force (0) against BoW (1) matching of the first keyframe with frame 5.
void BM_MatchKeyFrameWithFrame(benchmark::State& state) {
  SyntheticRun& run = Run();
  if (!run.system->Vocabulary()) {
    state.SkipWithError("no default vocabulary was built");
    return;
  }
  const auto keyframe = run.system->GetMap().KeyFrames().front();
  Frame frame = run.factory->Build(run.stamps[5], run.bgr[5], run.depth[5]);
  frame.has_bow = false;
  run.system->Vocabulary()->Transform(frame.Features().Descriptors(), &frame.bow,
                                      &frame.bow_features,
                                      DirectIndexLevel(*run.system->Vocabulary()));
  frame.has_bow = true;
  const bool bow = state.range(0) == 1;
  const OrbMatcher matcher;
  std::vector<std::shared_ptr<MapPoint>> matches;
  int count = 0;
  for (auto _ : state) {
    if (bow) {
      BowMatchOptions options;
      options.nn_ratio = 0.7;
      count = SearchByBow(*keyframe, frame, options, &matches);
    } else {
      std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
      count = matcher.SearchByDescriptors(*keyframe, frame, 0.7);
    }
    benchmark::DoNotOptimize(count);
  }
  state.SetLabel(std::string(bow ? "BoW" : "brute force") + ", " + std::to_string(count) +
                 " matches");
}
BENCHMARK(BM_MatchKeyFrameWithFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// Tracking against the reference keyframe alone (the tracker's fallback when the motion model
// fails), with brute-force (0) or BoW (1) matching: every frame of the synthetic run is matched
// with the last keyframe before it and its pose optimized from the previous frame's pose, as
// Tracker::TrackReferenceKeyFrame does. Counters: pose error against the full tracker's pose
// (itself ~2 mm from the ground truth), inliers, and frames that fail (< 15 matches or < 10
// inliers).
void BM_ReferenceTracking(benchmark::State& state) {
  SyntheticRun& run = Run();
  const auto& vocabulary = run.system->Vocabulary();
  if (!vocabulary) {
    state.SkipWithError("no default vocabulary was built");
    return;
  }
  const bool bow = state.range(0) == 1;
  const Trajectory tracked = run.system->CameraTrajectory();
  const auto keyframes = run.system->GetMap().KeyFrames();
  std::vector<Frame> frames;
  for (std::size_t i = 0; i < run.bgr.size(); ++i) {
    frames.push_back(run.factory->Build(run.stamps[i], run.bgr[i], run.depth[i]));
    vocabulary->Transform(frames.back().Features().Descriptors(), &frames.back().bow,
                          &frames.back().bow_features, DirectIndexLevel(*vocabulary));
    frames.back().has_bow = true;
  }
  const OrbMatcher matcher;
  double translation_error = 0.0, rotation_error = 0.0, inliers = 0.0;
  int evaluated = 0, failed = 0;
  for (auto _ : state) {
    translation_error = rotation_error = inliers = 0.0;
    evaluated = failed = 0;
    for (std::size_t i = 1; i < frames.size() && i < tracked.size(); ++i) {
      Frame& frame = frames[i];
      std::shared_ptr<KeyFrame> reference;
      for (const auto& keyframe : keyframes) {
        if (keyframe->FrameId() < static_cast<long>(i)) reference = keyframe;
      }
      if (!reference) continue;
      ++evaluated;
      std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
      int matches = 0;
      if (bow) {
        BowMatchOptions options;
        options.nn_ratio = 0.7;
        matches = SearchByBow(*reference, frame, options, &frame.map_points);
      } else {
        matches = matcher.SearchByDescriptors(*reference, frame, 0.7);
      }
      std::vector<PoseObservation> observations;
      for (std::size_t j = 0; j < frame.Size(); ++j) {
        if (!frame.map_points[j]) continue;
        const cv::KeyPoint& kp = frame.Features().KeypointsUn()[j];
        PoseObservation observation;
        observation.point_w = frame.map_points[j]->Position();
        observation.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
        observation.right_u = frame.Features().RightU(j);
        observation.inv_sigma2 = frame.Geometry().pyramid.inv_sigma2[kp.octave];
        observations.push_back(observation);
      }
      if (matches < 15 || observations.size() < 3) {
        ++failed;
        continue;
      }
      const PoseOptimizationResult result = OptimizePose(
          frame.Geometry().camera.Options(), tracked[i - 1].T_wc.Inverse(), observations);
      if (result.inliers < 10) {
        ++failed;
        continue;
      }
      const SE3 error = result.T_cw * tracked[i].T_wc;
      translation_error += error.Translation().norm();
      rotation_error += Eigen::AngleAxisd(error.Rotation()).angle() * 180.0 / M_PI;
      inliers += result.inliers;
    }
  }
  const int succeeded = std::max(1, evaluated - failed);
  state.counters["mean_error_mm"] = 1000.0 * translation_error / succeeded;
  state.counters["mean_error_deg"] = rotation_error / succeeded;
  state.counters["mean_inliers"] = inliers / succeeded;
  state.counters["failed"] = failed;
  state.counters["frames"] = evaluated;
  state.SetLabel(bow ? "BoW" : "brute force");
}
BENCHMARK(BM_ReferenceTracking)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One relocalization of frame 20 (BoW, database query, BoW matching, PnP, optimization, guided
// search) against the synthetic run's map. Since #31 every candidate is posed (two PnP tries
// each) and the places compared, where ORB-SLAM2 stopped at the first good candidate.
void BM_Relocalize(benchmark::State& state) {
  SyntheticRun& run = Run();
  if (!run.system->Vocabulary()) {
    state.SkipWithError("no default vocabulary was built");
    return;
  }
  Relocalizer relocalizer(run.system->Vocabulary(), run.system->KeyFrames(),
                          RelocalizationOptions());
  bool found = false;
  for (auto _ : state) {
    state.PauseTiming();
    Frame frame = run.factory->Build(run.stamps[20], run.bgr[20], run.depth[20]);
    state.ResumeTiming();
    found = relocalizer.Relocalize(frame);
    benchmark::DoNotOptimize(found);
  }
  state.SetLabel(std::string(found ? "found" : "not found") + ", " +
                 std::to_string(relocalizer.LastReport().candidates) + " candidates, " +
                 std::to_string(relocalizer.LastReport().inliers) + " inliers, " +
                 std::to_string(relocalizer.LastReport().hypotheses) + " poses in " +
                 std::to_string(relocalizer.LastReport().choice.places) + " places, " +
                 std::to_string(run.system->KeyFrames().Size()) + " keyframes");
}
BENCHMARK(BM_Relocalize)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
