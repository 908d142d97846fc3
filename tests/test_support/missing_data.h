// What a test does when an input it needs from outside the tree is missing (a shared model, an
// opencv-doc photograph, the build's default vocabulary, the CLI): it skips with a message, so
// the project still tests on a machine without them. CI sets DRVSLAM_REQUIRE_TEST_DATA=1, where
// all of them are installed: there a missing input fails the test, so CI cannot pass by skipping.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace drvslam::testing {

inline bool TestDataRequired() {
  const char* value = std::getenv("DRVSLAM_REQUIRE_TEST_DATA");
  return value != nullptr && std::string(value) != "" && std::string(value) != "0";
}

inline ::testing::TestPartResult::Type MissingDataOutcome() {
  return TestDataRequired() ? ::testing::TestPartResult::kFatalFailure
                            : ::testing::TestPartResult::kSkip;
}

}  // namespace drvslam::testing

// Use like GTEST_SKIP(): `if (path.empty()) DRVSLAM_MISSING_TEST_DATA() << path << " missing";`
// Skips the test, or fails it when DRVSLAM_REQUIRE_TEST_DATA is set.
#define DRVSLAM_MISSING_TEST_DATA()                                                          \
  return ::testing::internal::AssertHelper(                                                  \
             ::drvslam::testing::MissingDataOutcome(), __FILE__, __LINE__,                   \
             ::drvslam::testing::TestDataRequired() ? "missing test data "                   \
                                                      "(DRVSLAM_REQUIRE_TEST_DATA is set): " \
                                                    : "missing test data, skipped: ") =      \
             ::testing::Message()
