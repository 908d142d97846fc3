// From image files, folders and videos to vocabulary training data: which frames to use, their
// ORB descriptors, and the trained vocabulary. Shared by `drvslam vocab train`, the build-time
// default vocabulary and the place-recognition evaluation, so all three see images the same way.
#pragma once

#include <cstddef>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/tools/vocab/vocabulary_trainer.h"

namespace drvslam {

struct TrainingImageOptions {
  int max_images = 0;   // 0: no limit
  int video_step = 10;  // every Nth frame of a video, from the first
  // Larger images are shrunk (area interpolation) until their longer side is this many pixels,
  // close to the camera frames the vocabulary will see; 0 keeps every size.
  int max_side = 640;

  // Throws drvslam::Error naming the bad option.
  void Check() const;
};

// One image to use: a still image file, or one frame of a video.
struct TrainingImageSource {
  std::string path;
  int frame = -1;  // -1 for a still image

  // "path" or "path#frame".
  std::string Name() const;
};

// inputs: image files, folders (their image files, sorted by name; not recursive; videos
// inside are ignored, since they hold many frames they must be named explicitly) and videos
// (every video_step-th frame). In input order, cut at max_images. Throws drvslam::Error naming
// the path for a missing path, a folder without images, a file whose extension is neither an
// image's nor a video's, or a video that cannot be opened.
std::vector<TrainingImageSource> ListTrainingImages(const std::vector<std::string>& inputs,
                                                    const TrainingImageOptions& options);

// Visits each source as an 8-bit gray image (shrunk per max_side). A video yielding fewer
// frames than it announced ends early. Throws drvslam::Error naming the file for an image that
// does not decode or a video that cannot be opened.
void ForEachTrainingImage(
    const std::vector<TrainingImageSource>& sources, const TrainingImageOptions& options,
    const std::function<void(std::size_t index, const TrainingImageSource& source,
                             const cv::Mat& gray)>& visit);

struct ImageVocabularyOptions {
  TrainingImageOptions images;
  OrbExtractorOptions orb;
  int features_per_image = 1000;
  VocabularyTrainerOptions tree;

  void Check() const;
};

struct ImageVocabularyResult {
  BowVocabulary vocabulary;
  std::size_t images = 0;
  std::size_t descriptors = 0;
  double extract_seconds = 0.0;
  double train_seconds = 0.0;
};

// Lists the inputs, extracts ORB descriptors from every image and trains a vocabulary on them.
// progress(done, total) is called after each image when given.
ImageVocabularyResult TrainVocabularyFromImages(
    const std::vector<std::string>& inputs, const ImageVocabularyOptions& options,
    const std::function<void(std::size_t done, std::size_t total)>& progress = {});

}  // namespace drvslam
