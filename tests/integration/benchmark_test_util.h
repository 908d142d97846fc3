// Helpers the `drvslam benchmark` tests share (benchmark_test.cc and
// benchmark_end_to_end_test.cc): writing a text file, the message of an expected Error, and the
// shape of the Markdown tables.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam::test {

namespace fs = std::filesystem;

inline void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The message of the Error that `call` throws; fails the test when it throws none.
template <typename Call>
inline std::string ErrorOf(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error thrown";
  return "";
}

// Every row of each Markdown table has as many cells as its header.
inline void ExpectRectangularTables(const std::string& markdown) {
  std::istringstream lines(markdown);
  long header_bars = -1;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] != '|') {
      header_bars = -1;
      continue;
    }
    std::string unescaped = line;
    for (std::size_t at; (at = unescaped.find("\\|")) != std::string::npos;) {
      unescaped.erase(at, 2);
    }
    const long bars = std::count(unescaped.begin(), unescaped.end(), '|');
    if (header_bars < 0) header_bars = bars;
    EXPECT_EQ(bars, header_bars) << line;
  }
}

}  // namespace drvslam::test
