#include "drvslam/io/trajectory_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "test_support/error_message.h"
#include "test_support/missing_data.h"
#include "test_support/scratch_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> SplitFields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  std::string field;
  while (in >> field) fields.push_back(field);
  return fields;
}

std::vector<std::string> DataLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    lines.push_back(line);
  }
  return lines;
}

class TrajectoryIoTest : public testing::ScratchFolderTest {
 protected:
  std::string Write(const std::string& body, const std::string& name = "traj.txt") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << body;
    return path;
  }

  // Reading `body` must fail with a message naming the file, `line` (when > 0) and `needle`.
  void ExpectError(const std::string& body, int line, const std::string& needle) {
    SCOPED_TRACE("trajectory:\n" + body);
    const std::string path = Write(body);
    const std::string message = testing::ErrorMessageOf([&] { ReadTumTrajectory(path); });
    const std::string location = line > 0 ? path + ":" + std::to_string(line) + ":" : path;
    EXPECT_NE(message.find(location), std::string::npos) << message << " lacks " << location;
    EXPECT_NE(message.find(needle), std::string::npos) << message << " lacks " << needle;
  }
};

constexpr char kPose[] = " 0.1 0.2 0.3 0 0 0 1\n";

TEST_F(TrajectoryIoTest, WriteThenReadReproducesThePrintedNumbers) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Trajectory written;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Quaterniond q(uniform(random), uniform(random), uniform(random), uniform(random));
    const Eigen::Vector3d t(5.0 * uniform(random), 5.0 * uniform(random), uniform(random));
    written.push_back({1305031102.175304 + k * 0.0333 + 1e-7 * uniform(random), SE3(q, t)});
  }
  const std::string path = (dir_ / "written.txt").string();
  WriteTumTrajectory(path, written, "round trip");

  const std::vector<std::string> lines = DataLines(path);
  ASSERT_EQ(lines.size(), written.size());
  const Trajectory read = ReadTumTrajectory(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t k = 0; k < read.size(); ++k) {
    SCOPED_TRACE("pose " + std::to_string(k));
    EXPECT_EQ(lines[k], FormatTumPose(written[k]));
    const std::vector<std::string> fields = SplitFields(lines[k]);
    ASSERT_EQ(fields.size(), 8u);
    // Printing what was read gives the same stamp and translation text again (the quaternion may
    // move by one in the ninth decimal: reading renormalizes it).
    const std::vector<std::string> reprinted = SplitFields(FormatTumPose(read[k]));
    ASSERT_EQ(reprinted.size(), 8u);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(reprinted[i], fields[i]) << i;
    EXPECT_NEAR(read[k].timestamp, std::stod(fields[0]), 1e-9);
    const Eigen::Vector3d& t = read[k].T_wc.Translation();
    const Eigen::Quaterniond& q = read[k].T_wc.Quaternion();
    const double sign = q.w() < 0 ? -1.0 : 1.0;
    const double values[7] = {t.x(),        t.y(),        t.z(),       sign * q.x(),
                              sign * q.y(), sign * q.z(), sign * q.w()};
    for (int i = 0; i < 7; ++i) EXPECT_NEAR(values[i], std::stod(fields[i + 1]), 1e-9) << i;
    // And the read pose is the written one up to the printed precision.
    EXPECT_NEAR(read[k].timestamp, written[k].timestamp, 5e-7);
    EXPECT_LT((read[k].T_wc.Translation() - written[k].T_wc.Translation()).norm(), 1e-8);
    EXPECT_LT(RotationAngle(read[k].T_wc.Inverse() * written[k].T_wc), 1e-8);
  }
}

TEST_F(TrajectoryIoTest, WritesTheHeaderAndAPositiveQw) {
  const Eigen::Quaterniond negative_w(-0.5, 0.5, -0.5, 0.5);
  const std::string path = (dir_ / "out.txt").string();
  WriteTumTrajectory(path, {{2.5, SE3(negative_w, Eigen::Vector3d(1, 2, 3))}}, "from a test");
  std::ifstream in(path);
  std::string first, second, third;
  std::getline(in, first);
  std::getline(in, second);
  std::getline(in, third);
  EXPECT_EQ(first, "# from a test");
  EXPECT_EQ(second, "# timestamp tx ty tz qx qy qz qw");
  EXPECT_EQ(third,
            "2.500000 1.000000000 2.000000000 3.000000000 -0.500000000 0.500000000 -0.500000000 "
            "0.500000000");
}

TEST_F(TrajectoryIoTest, WritingToAMissingFolderIsAnError) {
  const std::string path = (dir_ / "no_such_folder" / "out.txt").string();
  try {
    WriteTumTrajectory(path, {{1.0, SE3()}});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST_F(TrajectoryIoTest, AcceptsCommasTabsCommentsAndBlankLines) {
  const std::string path = Write(
      "# ground truth trajectory\n"
      "\n"
      "1.0,0.5,-0.25,2,0,0,0,1\n"
      "   \n"
      "# a comment between poses\n"
      "2.0\t1\t2\t3\t0\t0\t1\t0\r\n"
      "  3.0   4  5  6   0 0 0 2  \n");
  const Trajectory trajectory = ReadTumTrajectory(path);
  ASSERT_EQ(trajectory.size(), 3u);
  EXPECT_DOUBLE_EQ(trajectory[0].timestamp, 1.0);
  EXPECT_DOUBLE_EQ(trajectory[0].T_wc.Translation().x(), 0.5);
  EXPECT_DOUBLE_EQ(trajectory[0].T_wc.Translation().y(), -0.25);
  EXPECT_DOUBLE_EQ(trajectory[0].T_wc.Translation().z(), 2.0);
  EXPECT_DOUBLE_EQ(trajectory[1].timestamp, 2.0);
  EXPECT_TRUE(trajectory[1].T_wc.Translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  // qz = 1: a half turn about z.
  EXPECT_NEAR(RotationAngle(trajectory[1].T_wc), M_PI, 1e-12);
  EXPECT_NEAR((trajectory[1].T_wc * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 2, 3)).norm(),
              0.0, 1e-12);
  // An unnormalized quaternion is normalized.
  EXPECT_NEAR(trajectory[2].T_wc.Quaternion().w(), 1.0, 1e-15);
  EXPECT_TRUE(trajectory[2].T_wc.Translation().isApprox(Eigen::Vector3d(4, 5, 6)));
}

TEST_F(TrajectoryIoTest, RejectsTooFewFields) {
  ExpectError("1" + std::string(kPose) + "2 0.1 0.2 0.3 0 0 1\n", 2, "expected 8 values");
}

TEST_F(TrajectoryIoTest, RejectsTooManyFields) {
  ExpectError("# header\n1 0.1 0.2 0.3 0 0 0 1 7\n", 2, "found 9");
}

TEST_F(TrajectoryIoTest, RejectsAFieldThatIsNotANumber) {
  ExpectError("1" + std::string(kPose) + "2" + kPose + "3 0.1 abc 0.3 0 0 0 1\n", 3,
              "'abc' is not a number");
  ExpectError("1.5x 0.1 0.2 0.3 0 0 0 1\n", 1, "'1.5x' is not a number");
}

TEST_F(TrajectoryIoTest, RejectsNaN) {
  ExpectError("1" + std::string(kPose) + "2 0.1 nan 0.3 0 0 0 1\n", 2, "not finite");
}

TEST_F(TrajectoryIoTest, RejectsInfinity) {
  ExpectError("\n\n1 0.1 0.2 0.3 0 0 0 inf\n", 3, "not finite");
  ExpectError("-inf" + std::string(kPose), 1, "not finite");
}

TEST_F(TrajectoryIoTest, RejectsAZeroQuaternion) {
  ExpectError("1 0.1 0.2 0.3 0 0 0 0\n", 1, "zero length");
}

TEST_F(TrajectoryIoTest, RejectsTimestampsThatGoBackwards) {
  ExpectError("5" + std::string(kPose) + "4" + kPose, 2, "does not increase");
  ExpectError("1" + std::string(kPose) + "2" + kPose + "2" + kPose + "1.5" + kPose, 4,
              "does not increase");
}

TEST_F(TrajectoryIoTest, RepeatedTimestampKeepsTheLaterPose) {
  // As in the real fr2/desk ground truth; the TUM tools keep the later line.
  const Trajectory trajectory = ReadTumTrajectory(
      Write("1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n2.0 2 0 0 0 0 0 1\n3.0 3 0 0 0 0 0 1\n"));
  ASSERT_EQ(trajectory.size(), 3u);
  EXPECT_EQ(trajectory[1].timestamp, 2.0);
  EXPECT_EQ(trajectory[1].T_wc.Translation().x(), 2.0);
  EXPECT_EQ(trajectory[2].timestamp, 3.0);
}

TEST_F(TrajectoryIoTest, RejectsAFileWithoutPoses) {
  ExpectError("", 0, "no poses");
  ExpectError("# only a comment\n\n", 0, "no poses");
  // Unless the caller says an empty trajectory is fine.
  EXPECT_TRUE(ReadTumTrajectory(Write("# nothing\n"), true).empty());
}

TEST_F(TrajectoryIoTest, RejectsAMissingFile) {
  const std::string path = (dir_ / "absent.txt").string();
  try {
    ReadTumTrajectory(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": file does not exist"), std::string::npos)
        << e.what();
  }
}

TEST(TumGroundTruthTest, ReadsTheRealGroundTruthFiles) {
  const fs::path root = fs::path(DRVSLAM_SHARED_DIR) / "tum-groundtruth";
  if (!fs::is_directory(root)) DRVSLAM_MISSING_TEST_DATA() << root << " is missing";
  int files = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(root)) {
    const fs::path path = entry.path() / "groundtruth.txt";
    if (!fs::is_regular_file(path)) continue;
    SCOPED_TRACE(path.string());
    ++files;
    const std::vector<std::string> lines = DataLines(path.string());
    ASSERT_FALSE(lines.empty());
    // One pose per data line, except a line repeating the previous stamp (fr2/desk has one).
    std::size_t repeats = 0;
    for (std::size_t k = 1; k < lines.size(); ++k) {
      if (SplitFields(lines[k])[0] == SplitFields(lines[k - 1])[0]) ++repeats;
    }
    const Trajectory trajectory = ReadTumTrajectory(path.string());
    EXPECT_EQ(trajectory.size(), lines.size() - repeats);
    EXPECT_LE(repeats, 1u);
    for (std::size_t k = 1; k < trajectory.size(); ++k) {
      ASSERT_LT(trajectory[k - 1].timestamp, trajectory[k].timestamp) << k;
    }
    const std::vector<std::string> first = SplitFields(lines.front());
    const std::vector<std::string> last = SplitFields(lines.back());
    ASSERT_EQ(first.size(), 8u);
    EXPECT_DOUBLE_EQ(trajectory.front().timestamp, std::stod(first[0]));
    EXPECT_DOUBLE_EQ(trajectory.back().timestamp, std::stod(last[0]));
    EXPECT_NEAR(trajectory.front().T_wc.Translation().x(), std::stod(first[1]), 1e-12);
    // A TUM sequence lasts between a few seconds and a few minutes.
    const double duration = trajectory.back().timestamp - trajectory.front().timestamp;
    EXPECT_GT(duration, 10.0);
    EXPECT_LT(duration, 300.0);
  }
  if (files == 0) DRVSLAM_MISSING_TEST_DATA() << "no groundtruth.txt under " << root;
}

}  // namespace
}  // namespace drvslam
