#include "drvslam/tools/vocab/training_images.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/feature/orb_extractor.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

std::string LowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// Whether the file name ends in one of `extensions` (lower case, with the dot), in any case.
bool HasExtension(const fs::path& path, std::initializer_list<const char*> extensions) {
  const std::string extension = LowerExtension(path);
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const char* e) { return extension == e; });
}

bool IsImageFile(const fs::path& path) {
  return HasExtension(path,
                      {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".webp"});
}

bool IsVideoFile(const fs::path& path) {
  return HasExtension(path,
                      {".avi", ".mp4", ".mkv", ".mov", ".mpg", ".mpeg", ".webm", ".m4v", ".wmv"});
}

cv::VideoCapture OpenVideo(const std::string& path) {
  cv::VideoCapture capture(path);
  if (!capture.isOpened()) throw Error(path + ": cannot open video");
  return capture;
}

// The announced frame count, or a count by reading when the container does not say.
int CountFrames(const std::string& path) {
  cv::VideoCapture capture = OpenVideo(path);
  const double announced = capture.get(cv::CAP_PROP_FRAME_COUNT);
  if (announced >= 1.0) return static_cast<int>(announced);
  int frames = 0;
  while (capture.grab()) ++frames;
  return frames;
}

cv::Mat ToGray(const cv::Mat& image, int max_side) {
  cv::Mat gray;
  if (image.channels() == 1) {
    gray = image;
  } else if (image.channels() == 4) {
    cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY);
  } else {
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  }
  if (gray.depth() != CV_8U) {
    // 16-bit images are scaled down to 8 bits.
    cv::Mat converted;
    gray.convertTo(converted, CV_8U, gray.depth() == CV_16U ? 1.0 / 256.0 : 1.0);
    gray = converted;
  }
  const int longer = std::max(gray.cols, gray.rows);
  if (max_side > 0 && longer > max_side) {
    const double scale = static_cast<double>(max_side) / longer;
    cv::Mat resized;
    cv::resize(gray, resized,
               cv::Size(std::max(1, static_cast<int>(std::lround(gray.cols * scale))),
                        std::max(1, static_cast<int>(std::lround(gray.rows * scale)))),
               0, 0, cv::INTER_AREA);
    gray = resized;
  }
  return gray;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void TrainingImageOptions::Check() const {
  if (max_images < 0) {
    throw Error("training images: max_images = " + std::to_string(max_images) +
                " must be >= 0 (0: no limit)");
  }
  if (video_step < 1) {
    throw Error("training images: video_step = " + std::to_string(video_step) + " must be >= 1");
  }
  if (max_side < 0 || (max_side > 0 && max_side < 32)) {
    throw Error("training images: max_side = " + std::to_string(max_side) +
                " must be 0 (keep) or >= 32");
  }
}

std::string TrainingImageSource::Name() const {
  return frame < 0 ? path : path + "#" + std::to_string(frame);
}

std::vector<TrainingImageSource> ListTrainingImages(const std::vector<std::string>& inputs,
                                                    const TrainingImageOptions& options) {
  options.Check();
  std::vector<TrainingImageSource> sources;
  const auto full = [&] {
    return options.max_images > 0 && static_cast<int>(sources.size()) >= options.max_images;
  };
  for (const std::string& input : inputs) {
    if (full()) break;
    std::error_code error;
    const fs::path path(input);
    if (fs::is_directory(path, error)) {
      std::vector<std::string> files;
      for (const fs::directory_entry& entry : fs::directory_iterator(path, error)) {
        if (entry.is_regular_file(error) && IsImageFile(entry.path())) {
          files.push_back(entry.path().string());
        }
      }
      if (error) throw Error(input + ": cannot list folder: " + error.message());
      if (files.empty()) throw Error(input + ": folder holds no image file");
      std::sort(files.begin(), files.end());
      for (const std::string& file : files) {
        if (full()) break;
        sources.push_back({file, -1});
      }
    } else if (fs::is_regular_file(path, error)) {
      if (IsImageFile(path)) {
        sources.push_back({input, -1});
      } else if (IsVideoFile(path)) {
        const int frames = CountFrames(input);
        if (frames == 0) throw Error(input + ": video holds no frame");
        for (int frame = 0; frame < frames && !full(); frame += options.video_step) {
          sources.push_back({input, frame});
        }
      } else {
        throw Error(input +
                    ": neither an image (.png .jpg .jpeg .bmp .tif .tiff .pgm .ppm "
                    ".webp) nor a video (.avi .mp4 .mkv .mov .mpg .mpeg .webm .m4v "
                    ".wmv)");
      }
    } else {
      throw Error(input + ": no such file or folder");
    }
  }
  return sources;
}

void ForEachTrainingImage(
    const std::vector<TrainingImageSource>& sources, const TrainingImageOptions& options,
    const std::function<void(std::size_t index, const TrainingImageSource& source,
                             const cv::Mat& gray)>& visit) {
  options.Check();
  cv::VideoCapture capture;
  std::string open_video;
  int next_frame = 0;
  bool video_ended = false;
  for (std::size_t index = 0; index < sources.size(); ++index) {
    const TrainingImageSource& source = sources[index];
    cv::Mat image;
    if (source.frame < 0) {
      image = cv::imread(source.path, cv::IMREAD_UNCHANGED);
      if (image.empty()) throw Error(source.path + ": cannot decode image");
    } else {
      // Frames are read in order; reopen when the video changes or a frame lies behind us.
      if (source.path != open_video || source.frame < next_frame) {
        capture = OpenVideo(source.path);
        open_video = source.path;
        next_frame = 0;
        video_ended = false;
      }
      if (video_ended) continue;
      while (next_frame < source.frame && capture.grab()) ++next_frame;
      if (next_frame < source.frame || !capture.read(image) || image.empty()) {
        video_ended = true;
        continue;
      }
      ++next_frame;
    }
    visit(index, source, ToGray(image, options.max_side));
  }
}

void ImageVocabularyOptions::Check() const {
  images.Check();
  orb.Check();
  tree.Check();
  if (features_per_image < 1) {
    throw Error("vocabulary training: features per image = " + std::to_string(features_per_image) +
                " must be >= 1");
  }
}

ImageVocabularyResult TrainVocabularyFromImages(
    const std::vector<std::string>& inputs, const ImageVocabularyOptions& options,
    const std::function<void(std::size_t done, std::size_t total)>& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const std::vector<TrainingImageSource> sources = ListTrainingImages(inputs, options.images);
  if (sources.empty()) throw Error("vocabulary training: no input images");
  OrbExtractor extractor(options.orb);
  std::vector<cv::Mat> descriptors;
  descriptors.reserve(sources.size());
  ImageVocabularyResult result;
  std::vector<cv::KeyPoint> keypoints;
  ForEachTrainingImage(sources, options.images,
                       [&](std::size_t index, const TrainingImageSource&, const cv::Mat& gray) {
                         cv::Mat image_descriptors;
                         extractor.Extract(gray, cv::Mat(), options.features_per_image, &keypoints,
                                           &image_descriptors);
                         result.descriptors += static_cast<std::size_t>(image_descriptors.rows);
                         descriptors.push_back(image_descriptors);
                         if (progress) progress(index + 1, sources.size());
                       });
  result.images = descriptors.size();
  result.extract_seconds = SecondsSince(start);
  const auto train_start = std::chrono::steady_clock::now();
  result.vocabulary = TrainVocabulary(descriptors, options.tree);
  result.train_seconds = SecondsSince(train_start);
  return result;
}

}  // namespace drvslam
