// The default vocabulary: one (k = 10, L = 6, ~140k words, 7.5 MB) the build trains from the
// opencv-doc sample photographs and every 10th frame of its sample videos, so relocalization and
// loop closing work when the user gives none. This says where it is; the build writes it to
// <build>/share/drvslam/default_vocab.bin, and an installed tree keeps the same bin/ ->
// ../share/drvslam/ layout.
#pragma once

#include <string>
#include <vector>

#include "drvslam/loop/bow_vocabulary.h"

namespace drvslam {

inline constexpr char kDefaultVocabularyFileName[] = "default_vocab.bin";
// An environment variable that, when set, names the file to use before any other.
inline constexpr char kDefaultVocabularyEnvironment[] = "DRVSLAM_DEFAULT_VOCABULARY";

// Where the default vocabulary is looked for, in order: $DRVSLAM_DEFAULT_VOCABULARY when set;
// ../share/drvslam/default_vocab.bin next to the running executable (works for bin/, tests/
// and bench/ of the build tree and for an installed tree); the build tree's share/drvslam as
// compiled in; the install prefix's share/drvslam as configured (CMAKE_INSTALL_PREFIX).
std::vector<std::string> DefaultVocabularyCandidates();

// The first candidate that is a regular file; empty when there is none (e.g. the build found
// no opencv-doc photographs to train on).
std::string DefaultVocabularyPath();

// Loads DefaultVocabularyPath(); throws drvslam::Error listing the places searched when none
// exists.
BowVocabulary LoadDefaultVocabulary();

}  // namespace drvslam
