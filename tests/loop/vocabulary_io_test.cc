// Vocabulary files: DBoW2 text and drvslam binary, round trips and every malformed-file error.
#include "drvslam/loop/vocabulary_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/tools/vocab/vocabulary_trainer.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

// One DBoW2 text node line: every descriptor byte equal to `byte`.
std::string NodeLine(const std::string& parent, const std::string& is_leaf, int byte,
                     const std::string& weight) {
  std::string line = parent + " " + is_leaf;
  for (int i = 0; i < 32; ++i) line += " " + std::to_string(byte);
  return line + " " + weight + "\n";
}

// TinyVocabulary() as DBoW2 would write it.
std::string TinyText() {
  return "2 2 0 0\n" + NodeLine("0", "0", 0, "0") + NodeLine("0", "0", 255, "0") +
         NodeLine("1", "1", 0, "1") + NodeLine("1", "1", 1, "2") + NodeLine("2", "1", 254, "3") +
         NodeLine("2", "1", 255, "4");
}

class VocabularyIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::ScratchFolder(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }

  std::string Path(const std::string& name) const { return folder_ + "/" + name; }

  std::string ReadBytes(const std::string& path) const {
    std::ifstream file(path, std::ios::binary);
    std::stringstream buffer;
    buffer << file.rdbuf();
    return buffer.str();
  }

  // Expects `read(path)` to throw an Error whose message names the file and holds `fragment`.
  template <typename Reader>
  void ExpectError(const Reader& read, const std::string& path, const std::string& fragment) {
    try {
      read(path);
      ADD_FAILURE() << "no error for " << path << " (expected '" << fragment << "')";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message: " << message << "\nexpected: " << fragment;
    }
  }

  void ExpectTextError(const std::string& content, const std::string& fragment) {
    const std::string path = Path("bad" + std::to_string(counter_++) + ".txt");
    test::WriteText(path, content);
    ExpectError([](const std::string& p) { return ReadTextVocabulary(p); }, path, fragment);
  }

  void ExpectBinaryError(const std::string& content, const std::string& fragment) {
    const std::string path = Path("bad" + std::to_string(counter_++) + ".bin");
    test::WriteText(path, content);
    ExpectError([](const std::string& p) { return ReadBinaryVocabulary(p); }, path, fragment);
  }

  std::string folder_;
  int counter_ = 0;
};

BowVocabulary TrainedTestVocabulary() {
  VocabularyTrainerOptions options;
  options.branching_factor = 6;
  options.depth = 3;
  return TrainVocabulary(test::ClusteredImages(40, 25, 40, 8, 31), options);
}

void ExpectSameTransforms(const BowVocabulary& a, const BowVocabulary& b) {
  const cv::Mat queries = test::RandomDescriptors(500, 77);
  for (int r = 0; r < queries.rows; ++r) {
    ASSERT_EQ(a.Transform(queries.row(r)), b.Transform(queries.row(r))) << "row " << r;
  }
  BowVector bow_a;
  BowVector bow_b;
  FeatureVector features_a;
  FeatureVector features_b;
  a.Transform(queries, &bow_a, &features_a, 1);
  b.Transform(queries, &bow_b, &features_b, 1);
  EXPECT_EQ(bow_a, bow_b);
  EXPECT_EQ(features_a, features_b);
}

TEST_F(VocabularyIoTest, ReadsDbow2TextAsWritten) {
  test::WriteText(Path("tiny.txt"), TinyText());
  const BowVocabulary vocabulary = ReadTextVocabulary(Path("tiny.txt"));
  EXPECT_TRUE(vocabulary == test::TinyVocabulary());
  EXPECT_EQ(vocabulary.WordCount(), 4u);
  EXPECT_EQ(vocabulary.WordNode(0), 3);
  EXPECT_DOUBLE_EQ(vocabulary.WordWeight(3), 4.0);
}

TEST_F(VocabularyIoTest, AcceptsOrbSlamSpacingCrLfAndBlankLines) {
  // ORBvoc.txt's header has a double space; files edited on Windows end lines in CR LF.
  std::string text = TinyText();
  text.replace(0, 8, "2 2  0 0\n");
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  test::WriteText(Path("crlf.txt"), crlf + "\r\n\n");
  EXPECT_TRUE(ReadTextVocabulary(Path("crlf.txt")) == test::TinyVocabulary());
}

TEST_F(VocabularyIoTest, TextRoundTripGivesIdenticalTreeAndTransforms) {
  const BowVocabulary vocabulary = TrainedTestVocabulary();
  WriteTextVocabulary(vocabulary, Path("voc.txt"));
  const BowVocabulary read = ReadTextVocabulary(Path("voc.txt"));
  EXPECT_TRUE(read == vocabulary);  // weights compared exactly
  ExpectSameTransforms(vocabulary, read);
  // The DBoW2 layout: header, then 35 fields per node.
  std::ifstream file(Path("voc.txt"));
  std::string header;
  std::string first_node;
  std::getline(file, header);
  std::getline(file, first_node);
  EXPECT_EQ(header, "6 3 0 0");
  std::istringstream fields(first_node);
  std::string field;
  int count = 0;
  while (fields >> field) ++count;
  EXPECT_EQ(count, 35);
}

TEST_F(VocabularyIoTest, BinaryRoundTripGivesIdenticalTreeAndTransforms) {
  const BowVocabulary vocabulary = TrainedTestVocabulary();
  WriteBinaryVocabulary(vocabulary, Path("voc.bin"));
  const BowVocabulary read = ReadBinaryVocabulary(Path("voc.bin"));
  EXPECT_TRUE(read == vocabulary);
  ExpectSameTransforms(vocabulary, read);
  EXPECT_EQ(std::filesystem::file_size(Path("voc.bin")), 36u + 45u * (vocabulary.NodeCount() - 1));
}

TEST_F(VocabularyIoTest, LoadVocabularyDetectsTheFormat) {
  const BowVocabulary vocabulary = test::TinyVocabulary();
  WriteVocabulary(vocabulary, Path("a.bin"), VocabularyFormat::kBinary);
  WriteVocabulary(vocabulary, Path("a.txt"), VocabularyFormat::kText);
  EXPECT_EQ(DetectVocabularyFormat(Path("a.bin")), VocabularyFormat::kBinary);
  EXPECT_EQ(DetectVocabularyFormat(Path("a.txt")), VocabularyFormat::kText);
  EXPECT_TRUE(LoadVocabulary(Path("a.bin")) == vocabulary);
  EXPECT_TRUE(LoadVocabulary(Path("a.txt")) == vocabulary);
  EXPECT_EQ(ParseVocabularyFormat("text"), VocabularyFormat::kText);
  EXPECT_EQ(ParseVocabularyFormat("binary"), VocabularyFormat::kBinary);
  EXPECT_THROW(ParseVocabularyFormat("yaml"), Error);
}

TEST_F(VocabularyIoTest, MissingFilesNameThePath) {
  const auto text = [](const std::string& p) { return ReadTextVocabulary(p); };
  const auto binary = [](const std::string& p) { return ReadBinaryVocabulary(p); };
  const auto load = [](const std::string& p) { return LoadVocabulary(p); };
  ExpectError(text, Path("missing.txt"), "cannot open");
  ExpectError(binary, Path("missing.bin"), "cannot open");
  ExpectError(load, Path("missing"), "cannot open");
}

TEST_F(VocabularyIoTest, TextHeaderErrors) {
  ExpectTextError("", "line 1: missing header");
  ExpectTextError("2 2 0\n", "line 1: header must be 'k L scoring weighting'");
  ExpectTextError("2 2 0 0 0\n", "line 1: header must be");
  ExpectTextError("k L 0 0\n", "line 1: header must be");
  ExpectTextError("2 2 1 0\n", "line 1: unsupported scoring type 1");
  ExpectTextError("2 2 0 2\n", "line 1: unsupported weighting type 2");
  ExpectTextError("1 2 0 0\n", "line 1: branching factor k = 1 out of range");
  ExpectTextError("2 0 0 0\n", "line 1: depth L = 0 out of range");
  ExpectTextError("2 99999999999999999999 0 0\n", "line 1: header must be");
  ExpectTextError("2 2 0 0\n", "the vocabulary has no nodes");
}

TEST_F(VocabularyIoTest, TextNodeLineErrors) {
  const std::string header = "2 2 0 0\n";
  const std::string a = NodeLine("0", "0", 0, "0");
  std::string short_line = a.substr(0, a.rfind(' ')) + "\n";  // no weight
  ExpectTextError(header + short_line, "line 2: expected 35 fields");
  ExpectTextError(header + short_line, "found 34");
  ExpectTextError(header + a.substr(0, a.size() - 1) + " 7\n", "line 2: expected 35 fields");
  ExpectTextError(header + a + NodeLine("0", "0", 256, "0"), "line 3: descriptor byte d0 '256'");
  ExpectTextError(header + a + NodeLine("0", "0", -1, "0"), "line 3: descriptor byte d0 '-1'");
  std::string letter = NodeLine("0", "0", 7, "0");
  letter.replace(letter.find(" 7 7"), 4, " 7 x");
  ExpectTextError(header + letter, "line 2: descriptor byte d1 'x'");
  ExpectTextError(header + NodeLine("0", "2", 0, "0"), "line 2: is_leaf '2' must be 0 or 1");
  ExpectTextError(header + NodeLine("0", "1", 0, "abc"), "line 2: weight 'abc' is not a number");
  ExpectTextError(header + NodeLine("0", "1", 0, "nan"), "line 2: weight nan");
  ExpectTextError(header + NodeLine("0", "1", 0, "-1"), "must be finite and >= 0");
  ExpectTextError(header + NodeLine("1.5", "1", 0, "0"), "line 2: parent id '1.5' is not an");
}

TEST_F(VocabularyIoTest, TextTreeErrors) {
  const std::string header = "2 2 0 0\n";
  // Parent ids must name an earlier node.
  ExpectTextError(header + NodeLine("5", "1", 0, "1"),
                  "line 2: parent id 5 of node 1 out of range [0, 1)");
  ExpectTextError(header + NodeLine("-1", "1", 0, "1"), "line 2: parent id -1 of node 1 out of");
  ExpectTextError(header + NodeLine("0", "1", 0, "1") + NodeLine("2", "1", 0, "1"),
                  "line 3: parent id 2 of node 2 out of range");
  // A leaf cannot have children.
  ExpectTextError(header + NodeLine("0", "1", 0, "1") + NodeLine("1", "1", 0, "1"),
                  "line 3: parent id 1 of node 2 is a leaf (line 2)");
  // At most k children.
  ExpectTextError(
      header + NodeLine("0", "1", 0, "1") + NodeLine("0", "1", 1, "1") + NodeLine("0", "1", 2, "1"),
      "line 4: node 0 gets more than k = 2 children");
  // No deeper than L.
  ExpectTextError("2 1 0 0\n" + NodeLine("0", "0", 0, "0") + NodeLine("1", "1", 0, "1"),
                  "line 3: node 2 sits at level 2, deeper than L = 1");
  // A file cut after whole lines leaves an inner node without children.
  const std::string tiny = TinyText();
  std::string cut = tiny.substr(0, tiny.find(NodeLine("2", "1", 254, "3")));
  ExpectTextError(cut, "line 3: node 2 is marked as an inner node but no node names it");
  // A file cut inside a line.
  ExpectTextError(tiny.substr(0, tiny.size() - 40), "line 7: expected 35 fields");
}

TEST_F(VocabularyIoTest, BinaryErrors) {
  WriteBinaryVocabulary(test::TinyVocabulary(), Path("good.bin"));
  const std::string good = ReadBytes(Path("good.bin"));
  ASSERT_EQ(good.size(), 36u + 6u * 45u);

  // The good file with the byte at `offset` set to `value`.
  const auto with_byte = [&good](std::size_t offset, char value) {
    std::string bad = good;
    bad[offset] = value;
    return bad;
  };
  ExpectBinaryError(with_byte(0, 'X'), "offset 0: not a drvslam binary vocabulary (bad magic)");
  ExpectBinaryError(TinyText(), "offset 0: not a drvslam binary vocabulary (bad magic)");
  ExpectBinaryError("", "offset 0: not a drvslam binary vocabulary");
  ExpectBinaryError(good.substr(0, 20), "offset 20: truncated header (20 bytes, expected 36)");
  ExpectBinaryError(with_byte(8, 2), "offset 8: unsupported binary vocabulary version 2");
  ExpectBinaryError(with_byte(12, 1), "offset 12: branching factor k = 1 out of range");
  ExpectBinaryError(with_byte(16, 40), "offset 12: depth L = 40 out of range");
  ExpectBinaryError(with_byte(20, 1), "offset 20: unsupported scoring type 1");
  ExpectBinaryError(with_byte(24, 3), "offset 24: unsupported weighting type 3");
  ExpectBinaryError(good.substr(0, good.size() - 10),
                    "offset 296: truncated: the header promises 6 nodes but the file ends "
                    "after 5 complete ones");
  ExpectBinaryError(good + "x", "offset 306: 1 unexpected bytes after the last of 6 nodes");
  const std::string no_nodes = with_byte(28, 0);  // node count 0 with node bytes following
  ExpectBinaryError(no_nodes, "offset 36: 270 unexpected bytes");
  ExpectBinaryError(no_nodes.substr(0, 36), "the vocabulary has no nodes");
  ExpectBinaryError(with_byte(36, 9),  // parent of node 1
                    "offset 36: parent id 9 of node 1 out of range [0, 1)");
  std::string bad = good;
  bad[36] = bad[37] = bad[38] = bad[39] = static_cast<char>(0xFF);
  ExpectBinaryError(bad, "offset 36: parent id 4294967295 of node 1 out of range");
  ExpectBinaryError(with_byte(40, 7),  // is_leaf of node 1
                    "offset 40: is_leaf byte 7 must be 0 or 1");
  // Node 1 becomes a leaf, yet nodes 3 and 4 name it as parent.
  ExpectBinaryError(with_byte(36 + 4, 1),
                    "offset 126: parent id 1 of node 3 is a leaf (offset 36)");
  bad = good;
  // Node 3's weight (record at 126, weight at +37) becomes a quiet NaN, little-endian.
  for (int i = 0; i < 6; ++i) bad[126 + 37 + i] = 0;
  bad[126 + 37 + 6] = static_cast<char>(0xF8);
  bad[126 + 37 + 7] = 0x7F;
  ExpectBinaryError(bad, "offset 126: weight nan of node 3 must be finite and >= 0");
}

TEST_F(VocabularyIoTest, WriteErrorsNameTheFile) {
  const std::string path = Path("no/such/folder/voc.bin");
  ExpectError([](const std::string& p) { WriteBinaryVocabulary(test::TinyVocabulary(), p); }, path,
              "cannot open vocabulary file for writing");
  ExpectError([](const std::string& p) { WriteTextVocabulary(test::TinyVocabulary(), p); }, path,
              "cannot open vocabulary file for writing");
  ExpectError([](const std::string& p) { WriteTextVocabulary(BowVocabulary(), p); },
              Path("empty.txt"), "cannot write an empty vocabulary");
}

}  // namespace
}  // namespace drvslam
