#include "drvslam/io/text_lines.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class TextLinesTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = drvslam::testing::UniqueTempFolder("drvslam_text_lines"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  // The message of the Error that `call` throws; empty when it throws none.
  template <typename Call>
  static std::string ErrorOf(Call call) {
    try {
      call();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(TextLinesTest, ForEachRecordGivesLineNumberWhereAndFieldsOfDataLinesOnly) {
  const std::string path = Write("list.txt", "# a comment\n\n1.5 rgb/a.png\n2.5,rgb/b.png\n");
  std::vector<int> lines;
  std::vector<std::string> wheres, names;
  ForEachRecord(path, 2, "2 fields (timestamp image_path)",
                [&](int line, const std::string& where, const std::vector<std::string>& fields) {
                  lines.push_back(line);
                  wheres.push_back(where);
                  names.push_back(fields[1]);
                });
  EXPECT_EQ(lines, (std::vector<int>{3, 4}));
  EXPECT_EQ(wheres, (std::vector<std::string>{path + ":3", path + ":4"}));
  EXPECT_EQ(names, (std::vector<std::string>{"rgb/a.png", "rgb/b.png"}));
}

TEST_F(TextLinesTest, ForEachRecordNamesLineShapeAndCountOfAShortLine) {
  const std::string path = Write("list.txt", "1.5 rgb/a.png\n# c\n2.5\n");
  int visited = 0;
  const std::string message = ErrorOf([&] {
    ForEachRecord(path, 2, "2 fields (timestamp image_path)",
                  [&](int, const std::string&, const std::vector<std::string>&) { ++visited; });
  });
  EXPECT_EQ(message, path + ":3: expected 2 fields (timestamp image_path), found 1");
  EXPECT_EQ(visited, 1);
}

TEST_F(TextLinesTest, ForEachLineSeesEveryLineAndStopsWhenTold) {
  const std::string path = Write("lines.txt", "# header [ns]\n\n1 2 3\n4 5 6\n7 8 9\n");
  std::vector<int> lines;
  std::vector<std::size_t> counts;
  ForEachLine(path, [&](int line, const std::string& text, const std::vector<std::string>& fields) {
    lines.push_back(line);
    counts.push_back(fields.size());
    return text != "4 5 6";
  });
  EXPECT_EQ(lines, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(counts, (std::vector<std::size_t>{3, 0, 3, 3}));
}

TEST_F(TextLinesTest, ForEachLineNamesAMissingFile) {
  const std::string path = (dir_ / "missing.txt").string();
  EXPECT_EQ(ErrorOf([&] {
              ForEachLine(path, [](int, const std::string&, const std::vector<std::string>&) {
                return true;
              });
            }),
            path + ": file does not exist");
}

TEST(ParseFiniteNumbersTest, ParsesTheFirstCountFields) {
  double values[3] = {0.0, 0.0, 0.0};
  ParseFiniteNumbers({"1.5", "-2", "3e2", "not read"}, 3, "f:1", values);
  EXPECT_EQ(values[0], 1.5);
  EXPECT_EQ(values[1], -2.0);
  EXPECT_EQ(values[2], 300.0);
}

TEST(ParseFiniteNumbersTest, ANonNumberIsReportedBeforeANonFiniteValue) {
  double values[3];
  try {
    ParseFiniteNumbers({"1", "nan", "x"}, 3, "f:7", values);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "f:7: 'x' is not a number");
  }
  try {
    ParseFiniteNumbers({"1", "inf", "2"}, 3, "f:8", values);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "f:8: value 'inf' is not finite");
  }
}

}  // namespace
}  // namespace drvslam
