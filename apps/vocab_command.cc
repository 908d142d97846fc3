// `drvslam vocab`: the bag-of-words vocabulary used for place recognition. `train` builds one
// from images or videos, `info` describes a file (or the build's default), `eval` measures how
// well vocabularies recognize places: changed views of images, or revisits in a sequence with
// ground truth.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/vocabulary_io.h"
#include "drvslam/tools/vocab/place_recognition_eval.h"
#include "drvslam/tools/vocab/training_images.h"
#include "progress_bar.h"

namespace {

// ---- train ----

struct TrainArguments {
  std::vector<std::string> inputs;
  std::string out;
  std::string format = "binary";
  drvslam::ImageVocabularyOptions options;
};

void RunTrain(const TrainArguments& args) {
  const drvslam::VocabularyFormat format = drvslam::ParseVocabularyFormat(args.format);
  args.options.Check();
  drvslam::ImageVocabularyResult result;
  {
    drvslam::cli::ProgressBar bar("extracting ORB");
    result = drvslam::TrainVocabularyFromImages(
        args.inputs, args.options,
        [&bar](std::size_t done, std::size_t total) { bar.Update(done, total); });
  }
  drvslam::WriteVocabulary(result.vocabulary, args.out, format);
  std::printf("images:      %zu\n", result.images);
  std::printf("descriptors: %zu\n", result.descriptors);
  std::printf("k, L:        %d, %d\n", result.vocabulary.BranchingFactor(),
              result.vocabulary.Depth());
  std::printf("words:       %zu (%zu nodes)\n", result.vocabulary.WordCount(),
              result.vocabulary.NodeCount());
  std::printf("time:        %.2f s extraction, %.2f s training\n", result.extract_seconds,
              result.train_seconds);
  std::printf("wrote %s (%s)\n", args.out.c_str(), drvslam::VocabularyFormatName(format));
}

void AddTrain(CLI::App* vocab) {
  auto args = std::make_shared<TrainArguments>();
  CLI::App* cmd = vocab->add_subcommand(
      "train", "train a vocabulary (hierarchical binary k-medians, TF-IDF) from images");
  cmd->add_option("--images", args->inputs,
                  "image folders (their images, sorted), image files or videos (every "
                  "--video-step-th frame)")
      ->required();
  cmd->add_option("--out", args->out, "vocabulary file to write")->required();
  cmd->add_option("--k", args->options.tree.branching_factor, "branching factor")
      ->capture_default_str();
  cmd->add_option("--levels", args->options.tree.depth, "depth L (up to k^L words)")
      ->capture_default_str();
  cmd->add_option("--features", args->options.features_per_image, "ORB features per image")
      ->capture_default_str();
  cmd->add_option("--max-images", args->options.images.max_images,
                  "use at most this many images (0: all)")
      ->capture_default_str();
  cmd->add_option("--video-step", args->options.images.video_step, "every Nth frame of a video")
      ->capture_default_str();
  cmd->add_option("--max-side", args->options.images.max_side,
                  "shrink larger images to this longer side in pixels (0: keep)")
      ->capture_default_str();
  cmd->add_option("--iterations", args->options.tree.max_iterations,
                  "most k-medians rounds per node")
      ->capture_default_str();
  cmd->add_option("--seed", args->options.tree.seed, "seed of the k-means++ seeding")
      ->capture_default_str();
  cmd->add_option("--format", args->format,
                  "binary (drvslam's, fast to load) or text (DBoW2/ORB-SLAM2 ORBvoc.txt)")
      ->capture_default_str();
  cmd->callback([args] { RunTrain(*args); });
}

// ---- info ----

std::string ResolveVocabularyPath(const std::string& given) {
  if (!given.empty() && given != "default") return given;
  const std::string path = drvslam::DefaultVocabularyPath();
  if (path.empty()) drvslam::LoadDefaultVocabulary();  // throws, listing where it looked
  return path;
}

void RunInfo(const std::string& given) {
  const std::string path = ResolveVocabularyPath(given);
  const drvslam::VocabularyFormat format = drvslam::DetectVocabularyFormat(path);
  const drvslam::BowVocabulary vocabulary = drvslam::LoadVocabulary(path);
  std::vector<std::size_t> words_at_level(vocabulary.Depth() + 1, 0);
  std::size_t zero_weight = 0;
  double min_weight = 0.0;
  double max_weight = 0.0;
  for (std::size_t word = 0; word < vocabulary.WordCount(); ++word) {
    const int id = static_cast<int>(word);
    ++words_at_level[vocabulary.NodeLevel(vocabulary.WordNode(id))];
    const double weight = vocabulary.WordWeight(id);
    if (weight == 0.0) ++zero_weight;
    min_weight = word == 0 ? weight : std::min(min_weight, weight);
    max_weight = word == 0 ? weight : std::max(max_weight, weight);
  }
  std::printf("file:    %s (%s)\n", path.c_str(), drvslam::VocabularyFormatName(format));
  std::printf("k:       %d\n", vocabulary.BranchingFactor());
  std::printf("L:       %d\n", vocabulary.Depth());
  std::printf("words:   %zu\n", vocabulary.WordCount());
  std::printf("nodes:   %zu\n", vocabulary.NodeCount());
  std::printf("weights: %.4f .. %.4f (%zu words weigh 0)\n", min_weight, max_weight, zero_weight);
  std::printf("words per level:");
  for (int level = 1; level <= vocabulary.Depth(); ++level) {
    std::printf(" %d:%zu", level, words_at_level[level]);
  }
  std::printf("\n");
}

void AddInfo(CLI::App* vocab) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd =
      vocab->add_subcommand("info", "print k, L and the word count of a vocabulary file");
  cmd->add_option("FILE", *file,
                  "vocabulary (text or binary); absent or 'default': the build's default");
  cmd->callback([file] { RunInfo(*file); });
}

// ---- eval ----

struct VocabEvalArguments {
  std::vector<std::string> vocabularies;
  std::vector<std::string> inputs;
  std::string sequence;
  drvslam::PlaceRecognitionSetOptions options;
  drvslam::RevisitSetOptions revisits;
  bool per_query = false;
};

void RunVocabEval(const VocabEvalArguments& args) {
  std::vector<std::string> paths;
  std::vector<drvslam::BowVocabulary> vocabularies;
  for (const std::string& given : args.vocabularies) {
    paths.push_back(ResolveVocabularyPath(given));
    vocabularies.push_back(drvslam::LoadVocabulary(paths.back()));
  }
  drvslam::PlaceRecognitionSet set;
  if (!args.sequence.empty()) {
    args.revisits.Check();
    set = drvslam::BuildRevisitSet(args.sequence, args.revisits);
    std::size_t candidates = 0;
    std::size_t true_matches = 0;
    for (std::size_t q = 0; q < set.queries.size(); ++q) {
      candidates += set.candidates[q].size();
      true_matches += set.true_matches[q].size();
    }
    std::printf(
        "keyframes: %zu (every %d frames), queries with a revisit: %zu, mean candidates "
        "%.1f, mean true matches %.1f (gap >= %.1f s, <= %.2f m, <= %.1f deg)\n",
        set.database.size(), args.revisits.frame_step, set.queries.size(),
        static_cast<double>(candidates) / set.queries.size(),
        static_cast<double>(true_matches) / set.queries.size(), args.revisits.min_gap_seconds,
        args.revisits.max_distance, args.revisits.max_angle_deg);
  } else {
    args.options.Check();
    set = drvslam::BuildPlaceRecognitionSet(args.inputs, args.options);
    std::printf(
        "database: %zu images, queries: %zu (rotation %.1f deg, scale %.2f, gain %.2f, "
        "offset %.1f, query offset %d)\n",
        set.database.size(), set.queries.size(), args.options.change.rotation_deg,
        args.options.change.scale, args.options.change.gain, args.options.change.offset,
        args.options.query_offset);
  }
  std::printf("%-10s %-10s %-10s %-9s %-9s %-9s %s\n", "words", "mean rank", "median", "recall@1",
              "recall@5", "ratio", "vocabulary");
  for (std::size_t v = 0; v < vocabularies.size(); ++v) {
    const drvslam::PlaceRecognitionResult result =
        drvslam::EvaluatePlaceRecognition(vocabularies[v], set);
    std::printf("%-10zu %-10.2f %-10.1f %-9.3f %-9.3f %-9.2f %s\n", vocabularies[v].WordCount(),
                result.MeanRank(), result.MedianRank(), result.RecallAt(1), result.RecallAt(5),
                result.MeanScoreRatio(), paths[v].c_str());
    if (args.per_query) {
      for (std::size_t q = 0; q < result.ranks.size(); ++q) {
        std::printf("  rank %3d  true %.4f  best other %.4f  %s\n", result.ranks[q],
                    result.true_scores[q], result.best_other_scores[q], set.query_names[q].c_str());
      }
    }
  }
}

void AddEval(CLI::App* vocab) {
  auto args = std::make_shared<VocabEvalArguments>();
  CLI::App* cmd = vocab->add_subcommand(
      "eval",
      "place-recognition quality: the rank of each query's true database image by BoW score");
  cmd->add_option("--vocab", args->vocabularies,
                  "vocabulary files to compare ('default': the build's default)")
      ->required();
  CLI::Option* images = cmd->add_option(
      "--images", args->inputs,
      "database images (folders, files or videos); queries are views of them changed by "
      "--rotate/--scale/--gain/--offset or the images --query-offset later");
  CLI::Option* sequence = cmd->add_option(
      "--sequence", args->sequence,
      "an RGB-D sequence with groundtruth.txt (TUM layout): every keyframe is a query among the "
      "keyframes --min-gap away, true where the camera revisits the same pose");
  images->excludes(sequence);
  cmd->add_option("--frame-step", args->revisits.frame_step,
                  "with --sequence: a keyframe every N frames")
      ->capture_default_str();
  cmd->add_option("--min-gap", args->revisits.min_gap_seconds,
                  "with --sequence: candidates lie at least this many seconds away")
      ->capture_default_str();
  cmd->add_option("--max-distance", args->revisits.max_distance,
                  "with --sequence: same place when camera centres are this close (m)")
      ->capture_default_str();
  cmd->add_option("--max-angle", args->revisits.max_angle_deg,
                  "with --sequence: ... and orientations differ by at most this (degrees)")
      ->capture_default_str();
  cmd->add_option("--max-images", args->options.images.max_images,
                  "use at most this many listed images (0: all)")
      ->capture_default_str();
  cmd->add_option("--video-step", args->options.images.video_step, "every Nth frame of a video")
      ->capture_default_str();
  cmd->add_option("--features", args->options.features_per_image, "ORB features per image")
      ->capture_default_str();
  cmd->add_option("--step", args->options.database_step, "the database is every Nth listed image")
      ->capture_default_str();
  cmd->add_option("--query-offset", args->options.query_offset,
                  "the query of a database image is the listed image this many later")
      ->capture_default_str();
  cmd->add_option("--rotate", args->options.change.rotation_deg,
                  "rotate queries by this many degrees")
      ->capture_default_str();
  cmd->add_option("--scale", args->options.change.scale, "zoom queries by this factor")
      ->capture_default_str();
  cmd->add_option("--gain", args->options.change.gain, "multiply query intensities")
      ->capture_default_str();
  cmd->add_option("--offset", args->options.change.offset, "add to query intensities")
      ->capture_default_str();
  cmd->add_flag("--per-query", args->per_query, "print every query's rank and scores");
  cmd->callback([args, images, sequence] {
    if (images->count() == 0 && sequence->count() == 0) {
      throw drvslam::Error("vocab eval: give --images or --sequence");
    }
    args->revisits.features_per_image = args->options.features_per_image;
    RunVocabEval(*args);
  });
}

const bool kVocabCommandRegistered = drvslam::cli::RegisterCommand("vocab", [](CLI::App& root) {
  CLI::App* vocab = root.add_subcommand(
      "vocab", "bag-of-words vocabularies for place recognition: train, info, eval");
  vocab->require_subcommand(1);
  AddTrain(vocab);
  AddInfo(vocab);
  AddEval(vocab);
});

}  // namespace
