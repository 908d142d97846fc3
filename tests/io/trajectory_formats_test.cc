#include "drvslam/io/trajectory_formats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/io/text_lines.h"
#include "test_support/error_message.h"
#include "test_support/scratch_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// `t` rounded to microseconds, as a TUM file stores it.
double Microseconds(double t) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", t);
  return std::stod(text);
}

// A trajectory with TUM-like stamps (seconds since 1970, microseconds) and every kind of
// rotation, the quaternion's w of either sign included.
Trajectory SampleTrajectory() {
  Trajectory trajectory;
  for (int k = 0; k < 40; ++k) {
    const double t = 1305031102.175304 + k * 0.033333;
    const Eigen::Vector3d axis = Eigen::Vector3d(std::sin(k), std::cos(0.7 * k), 0.3).normalized();
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.2 * k - 3.0, axis));
    const Eigen::Vector3d p(std::cos(0.5 * k) - 1.3, 0.01 * k, 2.0 * std::sin(0.2 * k));
    trajectory.push_back({Microseconds(t), SE3(q, p)});
  }
  return trajectory;
}

std::vector<std::string> Lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

class TrajectoryFormatsTest : public testing::ScratchFolderTest {
 protected:
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& body) const {
    std::ofstream(Path(name)) << body;
    return Path(name);
  }

  // Reading `path` must fail with a message containing each of `needles`.
  static void ExpectError(const std::string& path, const TrajectoryReadOptions& options,
                          const std::vector<std::string>& needles) {
    const std::string message = testing::ErrorMessageOf([&] { ReadTrajectory(path, options); });
    for (const std::string& needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos)
          << "'" << message << "' lacks '" << needle << "'";
    }
  }
};

void ExpectSamePoses(const Trajectory& written, const Trajectory& read) {
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    // Stamps come back bit for bit (microseconds in every format).
    EXPECT_EQ(read[i].timestamp, written[i].timestamp) << i;
    EXPECT_LT((read[i].T_wc.Translation() - written[i].T_wc.Translation()).norm(), 1e-8) << i;
    EXPECT_LT(RotationAngle(read[i].T_wc.Inverse() * written[i].T_wc), 1e-8) << i;
  }
}

class RoundTripTest : public TrajectoryFormatsTest,
                      public ::testing::WithParamInterface<TrajectoryFormat> {};

TEST_P(RoundTripTest, WriteThenReadGivesTheSamePosesAndIsDetected) {
  const TrajectoryFormat format = GetParam();
  const Trajectory written = SampleTrajectory();
  const std::string path = TrajectoryFilePath(Path("CameraTrajectory"), format);
  WriteTrajectory(path, written, format, "a comment");
  EXPECT_EQ(DetectTrajectoryFormat(path), format);
  ExpectSamePoses(written, ReadTrajectory(path));
  TrajectoryReadOptions explicit_format;
  explicit_format.format = format;
  ExpectSamePoses(written, ReadTrajectory(path, explicit_format));
}

INSTANTIATE_TEST_SUITE_P(AllFormats, RoundTripTest,
                         ::testing::Values(TrajectoryFormat::kTum, TrajectoryFormat::kKitti,
                                           TrajectoryFormat::kEuroc),
                         [](const auto& info) { return ToString(info.param); });

TEST_F(TrajectoryFormatsTest, TumOutputIsWhatWriteTumTrajectoryWrites) {
  const Trajectory trajectory = SampleTrajectory();
  WriteTrajectory(Path("a.txt"), trajectory, TrajectoryFormat::kTum, "header");
  WriteTumTrajectory(Path("b.txt"), trajectory, "header");
  EXPECT_EQ(Lines(Path("a.txt")), Lines(Path("b.txt")));
}

TEST_F(TrajectoryFormatsTest, KittiIsTwelveNumbersOfTheRowMajorPoseAndATimesFile) {
  const Trajectory trajectory = SampleTrajectory();
  const std::string path = Path("CameraTrajectory.txt");
  WriteTrajectory(path, trajectory, TrajectoryFormat::kKitti, "not written");
  EXPECT_EQ(KittiTimesPath(path), Path("CameraTrajectory_times.txt"));
  const std::vector<std::string> poses = Lines(path);
  const std::vector<std::string> times = Lines(KittiTimesPath(path));
  ASSERT_EQ(poses.size(), trajectory.size());
  ASSERT_EQ(times.size(), trajectory.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::vector<std::string> fields = SplitFields(poses[i]);
    ASSERT_EQ(fields.size(), 12u) << poses[i];
    const Eigen::Matrix4d m = trajectory[i].T_wc.Matrix();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(std::stod(fields[4 * r + c]), m(r, c), 1e-9);
    }
    EXPECT_EQ(std::stod(times[i]), trajectory[i].timestamp);
  }
}

TEST_F(TrajectoryFormatsTest, EurocIsTheGroundTruthCsvLayoutInNanoseconds) {
  Trajectory trajectory;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()));
  trajectory.push_back({1403715274.302142, SE3(q, Eigen::Vector3d(0.5, -1.0, 2.0))});
  WriteTrajectory(Path("t.csv"), trajectory, TrajectoryFormat::kEuroc);
  const std::vector<std::string> lines = Lines(Path("t.csv"));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], "
            "q_RS_y [], q_RS_z []");
  char expected[256];
  std::snprintf(expected, sizeof(expected),
                "1403715274302142000,0.500000000,-1.000000000,"
                "2.000000000,%.9f,0.000000000,%.9f,0.000000000",
                q.w(), q.y());
  EXPECT_EQ(lines[1], expected);
}

TEST_F(TrajectoryFormatsTest, ReadsEurocGroundTruthWithItsSeventeenColumns) {
  // The first lines of MH_01_easy's state_groundtruth_estimate0/data.csv, shortened.
  const std::string path = Write(
      "data.csv",
      "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad "
      "s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m "
      "s^-2], b_a_RS_S_z [m s^-2]\n"
      "1403636580838555648,4.688319,-1.786938,0.783338,0.534108,-0.153029,-0.827383,-0.082152,"
      "-0.027876,0.033207,0.800006,-0.003172,0.021267,0.078502,-0.025266,0.136696,0.075593\n"
      "1403636580843555328,4.688177,-1.786770,0.787350,0.534640,-0.152990,-0.826976,-0.082863,"
      "-0.029272,0.033992,0.804771,-0.003172,0.021267,0.078502,-0.025266,0.136696,0.075593\n");
  EXPECT_EQ(DetectTrajectoryFormat(path), TrajectoryFormat::kEuroc);
  const Trajectory trajectory = ReadTrajectory(path);
  ASSERT_EQ(trajectory.size(), 2u);
  EXPECT_NEAR(trajectory[0].timestamp, 1403636580.838555648, 1e-6);
  // Seconds near 1.4e9 in a double keep about 0.2 microseconds.
  EXPECT_NEAR(trajectory[1].timestamp - trajectory[0].timestamp, 0.00499968, 1e-6);
  EXPECT_NEAR(trajectory[0].T_wc.Translation().x(), 4.688319, 1e-12);
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(0.534108, -0.153029, -0.827383, -0.082152).normalized();
  EXPECT_LT(q.angularDistance(trajectory[0].T_wc.Quaternion()), 1e-9);
}

TEST_F(TrajectoryFormatsTest, DetectsByContent) {
  EXPECT_EQ(DetectTrajectoryFormat(Write("tum", "# c\n1.5 0 0 0 0 0 0 1\n")),
            TrajectoryFormat::kTum);
  // TUM tools accept commas; a stamp with a decimal point is not EuRoC's nanoseconds.
  EXPECT_EQ(DetectTrajectoryFormat(Write("tum_commas", "1.5,0,0,0,0,0,0,1\n")),
            TrajectoryFormat::kTum);
  EXPECT_EQ(DetectTrajectoryFormat(Write("euroc", "1500000000,0,0,0,1,0,0,0\n")),
            TrajectoryFormat::kEuroc);
  EXPECT_EQ(DetectTrajectoryFormat(Write("kitti", "1 0 0 0 0 1 0 0 0 0 1 0\n")),
            TrajectoryFormat::kKitti);
  EXPECT_EQ(DetectTrajectoryFormat(Write("empty", "# nothing\n")), TrajectoryFormat::kTum);
}

TEST_F(TrajectoryFormatsTest, UndetectableFileIsAnErrorNamingFileAndLine) {
  const std::string path = Write("odd.txt", "# header\n\n1 2 3 4 5\n");
  const std::string message = testing::ErrorMessageOf([&] { DetectTrajectoryFormat(path); });
  EXPECT_NE(message.find(path + ":3: cannot tell the trajectory format"), std::string::npos)
      << message;
}

TEST_F(TrajectoryFormatsTest, KittiWithoutTimesIsStampedWithTheFrameIndex) {
  const std::string path =
      Write("poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0.5 0 1 0 0 0 0 1 0\n");
  const Trajectory trajectory = ReadTrajectory(path);
  ASSERT_EQ(trajectory.size(), 2u);
  EXPECT_EQ(trajectory[0].timestamp, 0.0);
  EXPECT_EQ(trajectory[1].timestamp, 1.0);
  EXPECT_DOUBLE_EQ(trajectory[1].T_wc.Translation().x(), 0.5);
}

TEST_F(TrajectoryFormatsTest, KittiTakesTimesTxtBesideItOrTheGivenFile) {
  const std::string path = Write("00.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0.5 0 1 0 0 0 0 1 0\n");
  Write("times.txt", "0.000000e+00\n1.036400e-01\n");
  Trajectory trajectory = ReadTrajectory(path);
  ASSERT_EQ(trajectory.size(), 2u);
  EXPECT_EQ(trajectory[1].timestamp, 0.10364);
  TrajectoryReadOptions options;
  options.kitti_times = Write("other_times.txt", "5\n6\n");
  trajectory = ReadTrajectory(path, options);
  EXPECT_EQ(trajectory[1].timestamp, 6.0);
}

TEST_F(TrajectoryFormatsTest, BadKittiFilesAreErrorsNamingFileAndLine) {
  ExpectError(Write("short.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n"), {},
              {Path("short.txt") + ":2", "expected 12 values", "found 11"});
  ExpectError(Write("skew.txt", "1 0 0 0 0 1 0 0 0 0.5 1 0\n"), {},
              {Path("skew.txt") + ":1", "not a rotation"});
  ExpectError(Write("mirror.txt", "1 0 0 0 0 1 0 0 0 0 -1 0\n"), {},
              {Path("mirror.txt") + ":1", "not a rotation"});
  TrajectoryReadOptions kitti;
  kitti.format = TrajectoryFormat::kKitti;
  ExpectError(Write("nan.txt", "1 0 0 nan 0 1 0 0 0 0 1 0\n"), kitti,
              {Path("nan.txt") + ":1", "'nan' is not finite"});
  const std::string poses = Write("p.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 0\n");
  kitti.kitti_times = Write("t.txt", "1\n");
  ExpectError(poses, kitti, {Path("t.txt"), "has 1 timestamps", "has 2 poses"});
  kitti.kitti_times = Write("back.txt", "2\n1\n");
  ExpectError(poses, kitti, {Path("back.txt") + ":2", "does not increase"});
  kitti.kitti_times = Path("missing_times.txt");
  ExpectError(poses, kitti, {Path("missing_times.txt"), "does not exist"});
}

TEST_F(TrajectoryFormatsTest, BadEurocFilesAreErrorsNamingFileAndLine) {
  TrajectoryReadOptions euroc;
  euroc.format = TrajectoryFormat::kEuroc;
  ExpectError(Write("short.csv", "#timestamp [ns]\n100,0,0,0,1,0,0\n"), euroc,
              {Path("short.csv") + ":2", "expected at least 8 values", "found 7"});
  ExpectError(Write("seconds.csv", "1.5,0,0,0,1,0,0,0\n"), euroc,
              {Path("seconds.csv") + ":1", "'1.5' is not an integer number of nanoseconds"});
  ExpectError(Write("zero.csv", "100,0,0,0,0,0,0,0\n"), euroc,
              {Path("zero.csv") + ":1", "zero length"});
  ExpectError(Write("back.csv", "200,0,0,0,1,0,0,0\n100,0,0,0,1,0,0,0\n"), euroc,
              {Path("back.csv") + ":2", "does not increase"});
  ExpectError(Write("none.csv", "#timestamp [ns]\n"), euroc, {Path("none.csv"), "no poses"});
}

TEST_F(TrajectoryFormatsTest, UnknownFormatNameIsAnErrorNamingTheOption) {
  EXPECT_EQ(testing::ErrorMessageOf([] { ParseTrajectoryFormat("csv", "--trajectory-format"); }),
            "--trajectory-format = 'csv' must be tum, kitti or euroc");
}

}  // namespace
}  // namespace drvslam
