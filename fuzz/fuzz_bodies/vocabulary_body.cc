// Vocabulary files (Relocalization.vocabulary, `drvslam vocab`): LoadVocabulary picks text or
// binary by the magic; a vocabulary that loads must also work, so a few descriptors go down its
// tree into a bag of words, as loop detection and relocalization use it.
#include <opencv2/core.hpp>
#include <string>

#include "drvslam/loop/bow_vector.h"
#include "drvslam/loop/relocalizer.h"
#include "drvslam/loop/vocabulary_io.h"
#include "fuzz_bodies/fuzz_bodies.h"
#include "fuzz_bodies/rejection.h"
#include "fuzz_bodies/scratch_file.h"

namespace drvslam::fuzz {

void RunVocabularyBody(const std::uint8_t* data, std::size_t size) {
  const std::string path = WriteScratchFile("vocabulary.voc", data, size);
  AllowRejection([&] {
    const BowVocabulary vocabulary = LoadVocabulary(path);
    if (vocabulary.Empty()) return;
    // Rows of all zeros, all ones and a ramp: they take different branches of most trees.
    cv::Mat descriptors(3, 32, CV_8UC1, cv::Scalar(0));
    descriptors.row(1).setTo(cv::Scalar(255));
    for (int column = 0; column < 32; ++column) {
      descriptors.at<std::uint8_t>(2, column) = static_cast<std::uint8_t>(column * 8);
    }
    BowVector bow;
    FeatureVector features;
    vocabulary.Transform(descriptors, &bow, &features, DirectIndexLevel(vocabulary));
  });
}

}  // namespace drvslam::fuzz
