// Bag-of-words vocabulary costs: transforming an image's 1000 ORB descriptors, scoring two
// images, and loading a 1M-word (k = 10, L = 6, ORBvoc.txt-sized) vocabulary in both formats.
// The 1M-word tree is synthetic (training one needs ~10^7 descriptors), built in DBoW2's node
// order; descent costs depend only on its shape. Also run on the build's default vocabulary
// and, when DRVSLAM_BENCH_VOCABULARY names a file (e.g. ORBvoc.txt), on that one.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

#include "drvslam/feature/orb_extractor.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/vocabulary_builder.h"
#include "drvslam/loop/vocabulary_io.h"

namespace drvslam {
namespace {

constexpr int kDirectIndexLevelsUp = 4;  // ORB-SLAM's choice: level L - 4 groups features

// Appends the children of `node` at `level`, then each child's subtree (DBoW2's order).
void GrowFullTree(VocabularyBuilder* builder, int node, int level, int k, int depth,
                  std::mt19937_64* rng) {
  uint8_t descriptor[32];
  std::vector<int> children;
  for (int c = 0; c < k; ++c) {
    for (uint8_t& byte : descriptor) byte = static_cast<uint8_t>((*rng)());
    const bool leaf = level == depth;
    const double weight = leaf ? 0.5 + static_cast<double>((*rng)() % 1000) / 200.0 : 0.0;
    children.push_back(builder->AddNode(node, leaf, descriptor, weight, "node", 0));
  }
  if (level == depth) return;
  for (int child : children) GrowFullTree(builder, child, level + 1, k, depth, rng);
}

const BowVocabulary& SyntheticMillionWords() {
  static const BowVocabulary vocabulary = [] {
    VocabularyBuilder builder(10, 6, "synthetic", "k=10 L=6");
    builder.Reserve(1111111);
    std::mt19937_64 rng(1);
    GrowFullTree(&builder, 0, 1, 10, 6, &rng);
    return builder.Finish();
  }();
  return vocabulary;
}

// 1000 ORB descriptors of opencv-doc photographs (random bytes when they are missing).
const cv::Mat& ImageDescriptors(int which) {
  static const std::vector<cv::Mat> descriptors = [] {
    std::vector<cv::Mat> result;
    OrbExtractor extractor{OrbExtractorOptions{}};
    for (const char* name : {"graf1.png", "home.jpg"}) {
      cv::Mat gray =
          cv::imread(std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + name, cv::IMREAD_GRAYSCALE);
      cv::Mat d;
      if (!gray.empty()) {
        cv::resize(gray, gray, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
        std::vector<cv::KeyPoint> keypoints;
        extractor.Extract(gray, cv::Mat(), 1000, &keypoints, &d);
      } else {
        d = cv::Mat(1000, 32, CV_8UC1);
        cv::randu(d, 0, 256);
      }
      result.push_back(d);
    }
    return result;
  }();
  return descriptors[which];
}

// The default vocabulary and the one named by DRVSLAM_BENCH_VOCABULARY; null when absent.
const BowVocabulary* DefaultVocabulary() {
  static const std::unique_ptr<BowVocabulary> vocabulary = [] {
    const std::string path = DefaultVocabularyPath();
    return path.empty() ? nullptr : std::make_unique<BowVocabulary>(LoadVocabulary(path));
  }();
  return vocabulary.get();
}

const BowVocabulary* GivenVocabulary() {
  static const std::unique_ptr<BowVocabulary> vocabulary = [] {
    const char* path = std::getenv("DRVSLAM_BENCH_VOCABULARY");
    return path == nullptr ? nullptr : std::make_unique<BowVocabulary>(LoadVocabulary(path));
  }();
  return vocabulary.get();
}

const BowVocabulary* Pick(int which) {
  if (which == 0) return &SyntheticMillionWords();
  return which == 1 ? DefaultVocabulary() : GivenVocabulary();
}

// The vocabulary range(0) names; null, with the benchmark marked skipped, when it is not available.
const BowVocabulary* PickOrSkip(benchmark::State& state) {
  const BowVocabulary* vocabulary = Pick(static_cast<int>(state.range(0)));
  if (vocabulary == nullptr) state.SkipWithError("vocabulary not available");
  return vocabulary;
}

const char* kNames[] = {"synthetic k10 L6", "default", "DRVSLAM_BENCH_VOCABULARY"};

void BM_Transform1000Descriptors(benchmark::State& state) {
  const BowVocabulary* vocabulary = PickOrSkip(state);
  if (vocabulary == nullptr) return;
  const cv::Mat& descriptors = ImageDescriptors(0);
  const int level = std::max(0, vocabulary->Depth() - kDirectIndexLevelsUp);
  BowVector bow;
  FeatureVector features;
  for (auto _ : state) {
    vocabulary->Transform(descriptors, &bow, &features, level);
    benchmark::DoNotOptimize(bow);
  }
  state.SetItemsProcessed(state.iterations() * descriptors.rows);
  state.SetLabel(std::string(kNames[state.range(0)]) + ", " +
                 std::to_string(vocabulary->WordCount()) + " words, " +
                 std::to_string(descriptors.rows) + " descriptors, " + std::to_string(bow.size()) +
                 " bow entries");
}
BENCHMARK(BM_Transform1000Descriptors)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// The tree descent alone, without building the BowVector and FeatureVector maps.
void BM_Descend1000Descriptors(benchmark::State& state) {
  const BowVocabulary* vocabulary = PickOrSkip(state);
  if (vocabulary == nullptr) return;
  const cv::Mat& descriptors = ImageDescriptors(0);
  for (auto _ : state) {
    int sum = 0;
    for (int r = 0; r < descriptors.rows; ++r) sum += vocabulary->Transform(descriptors.ptr(r));
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * descriptors.rows);
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_Descend1000Descriptors)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

void BM_ScoreTwoImages(benchmark::State& state) {
  const BowVocabulary* vocabulary = PickOrSkip(state);
  if (vocabulary == nullptr) return;
  BowVector a;
  BowVector b;
  vocabulary->Transform(ImageDescriptors(0), &a, nullptr, 0);
  vocabulary->Transform(ImageDescriptors(1), &b, nullptr, 0);
  double score = 0.0;
  for (auto _ : state) {
    score = BowVocabulary::Score(a, b);
    benchmark::DoNotOptimize(score);
  }
  state.SetLabel(std::string(kNames[state.range(0)]) + ", entries " + std::to_string(a.size()) +
                 " and " + std::to_string(b.size()) + ", score " + std::to_string(score));
}
BENCHMARK(BM_ScoreTwoImages)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// The synthetic 1M-word vocabulary written once per format, then read back.
std::string SyntheticFile(VocabularyFormat format) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            (std::string("drvslam_bench_vocab_1m.") +
                             (format == VocabularyFormat::kText ? "txt" : "bin")))
                               .string();
  static bool written[2] = {false, false};
  if (!written[static_cast<int>(format)]) {
    WriteVocabulary(SyntheticMillionWords(), path, format);
    written[static_cast<int>(format)] = true;
  }
  return path;
}

void BM_LoadMillionWords(benchmark::State& state) {
  const VocabularyFormat format =
      state.range(0) == 0 ? VocabularyFormat::kBinary : VocabularyFormat::kText;
  const std::string path = SyntheticFile(format);
  std::size_t words = 0;
  for (auto _ : state) {
    const BowVocabulary vocabulary = LoadVocabulary(path);
    words = vocabulary.WordCount();
  }
  state.SetLabel(std::string(VocabularyFormatName(format)) + ", " + std::to_string(words) +
                 " words, " + std::to_string(std::filesystem::file_size(path) >> 20) + " MiB");
}
BENCHMARK(BM_LoadMillionWords)->Arg(0)->Arg(1)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
