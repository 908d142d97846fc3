// Cost of completing one person's mask with depth (dynamic/depth_mask_completion.h) on a 640x480
// frame: a standing person 1.5 m away in front of a wall 3 m away, whose network mask misses
// an arm and the legs (the missing parts are depth-connected to the body, as on the real Bonn
// crowd sequence). Each iteration completes a fresh copy of the network's mask; the copy (a
// 300 KB memcpy) is part of the time. Arg: the person's height in pixels (near people are tall).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/dynamic/depth_mask_completion.h"

namespace {

using namespace drvslam;

struct PersonScene {
  cv::Mat depth;  // CV_32FC1 metres
  Instance network_mask;
};

PersonScene MakeScene(int height) {
  PersonScene scene;
  scene.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(3.0f));
  const int width = height / 3;
  const cv::Rect body(320 - width / 2, 470 - height, width, height);
  const cv::Rect arm(body.x + body.width, body.y + height / 5, width / 2, height / 8);
  cv::Mat person = cv::Mat::zeros(scene.depth.size(), CV_8UC1);
  cv::ellipse(person, (body.tl() + body.br()) / 2, body.size() / 2, 0, 0, 360, 255, cv::FILLED);
  cv::rectangle(person, arm, 255, cv::FILLED);
  scene.depth.setTo(1.5f, person);
  // The network's mask: the body without the arm and without the lowest third (the legs).
  cv::Mat mask = person.clone();
  mask(arm).setTo(0);
  mask(cv::Rect(0, body.y + 2 * height / 3, 640, 480 - (body.y + 2 * height / 3))).setTo(0);
  scene.network_mask.class_id = 0;
  scene.network_mask.mask = mask;
  scene.network_mask.box = cv::boundingRect(mask);
  return scene;
}

void BM_CompleteMaskWithDepth(benchmark::State& state) {
  const PersonScene scene = MakeScene(static_cast<int>(state.range(0)));
  const MaskCompletionOptions options;
  int added = 0;
  for (auto _ : state) {
    Instance instance = scene.network_mask;
    instance.mask = scene.network_mask.mask.clone();
    added = CompleteMaskWithDepth(instance, scene.depth, options);
    benchmark::DoNotOptimize(added);
  }
  state.counters["pixels_added"] = added;
  state.counters["mask_pixels"] = cv::countNonZero(scene.network_mask.mask);
}
BENCHMARK(BM_CompleteMaskWithDepth)->Arg(200)->Arg(420)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
