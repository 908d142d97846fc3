// The viewer's pieces without a browser: the run data the page gets, the self-contained page,
// the encodings, the ground-truth overlay, the server's HTTP answers and its bad-input errors,
// and the CLI's exit status for a port in use and a run folder without outputs. The page itself
// is tested in headless Chromium (web/test/viewer_browser_test.mjs, registered beside this).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/dense/point_cloud_io.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/viewer/run_data.h"
#include "drvslam/tools/viewer/viewer_json.h"
#include "drvslam/tools/viewer/viewer_page.h"
#include "drvslam/tools/viewer/web_server.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  return drvslam::testing::UniqueTempFolder("drvslam_viewer_" + name);
}

struct CliResult {
  int status = -1;
  std::string output;
};

CliResult RunCli(const std::string& arguments) {
  CliResult result;
  const std::string command = std::string(DRVSLAM_CLI) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (fgets(buffer, sizeof(buffer), pipe)) result.output += buffer;
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// A plain HTTP/1.0 GET on 127.0.0.1; returns the whole response (status line, headers, body).
std::string HttpGet(int port, const std::string& path) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    close(fd);
    return "";
  }
  const std::string request = "GET " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
  if (write(fd, request.data(), request.size()) != static_cast<ssize_t>(request.size())) {
    close(fd);
    return "";
  }
  std::string response;
  char buffer[4096];
  ssize_t got = 0;
  while ((got = read(fd, buffer, sizeof(buffer))) > 0) response.append(buffer, got);
  close(fd);
  return response;
}

StampedPose Pose(double t, double x, double y, double z) {
  return {t, SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, y, z))};
}

// A run folder as drvslam run leaves it, small: 5 poses, 2 keyframes, 7 map points, 1000 dense
// points, and a ground truth beside it (the estimate shifted by 1 m in x).
class RunFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = FreshDir("run");
    Trajectory estimate, truth;
    for (int i = 0; i < 5; ++i) {
      estimate.push_back(Pose(i * 0.1, 0.1 * i, 0.02 * i * i, 0.0));
      truth.push_back(Pose(i * 0.1, 0.1 * i + 1.0, 0.02 * i * i, 0.0));
    }
    WriteTumTrajectory((dir_ / "CameraTrajectory.txt").string(), estimate);
    WriteTumTrajectory((dir_ / "KeyFrameTrajectory.txt").string(), {estimate[0], estimate[3]});
    WriteTumTrajectory((dir_ / "truth.txt").string(), truth);
    DenseCloud sparse(7);
    WritePlyCloud((dir_ / "sparse_map.ply").string(), sparse);
    DenseCloud dense(1000);
    for (std::size_t i = 0; i < dense.size(); ++i) dense[i].position.x() = static_cast<float>(i);
    WritePlyCloud((dir_ / "dense_map.ply").string(), dense);
    std::ofstream stats(dir_ / "stats.json");
    stats << R"({"frames": 5, "tracked": 5, "stages": {"total": {"median_ms": 3.0}},
                 "loop": {"loops": [{"keyframe": 3, "loop_keyframe": 0, "timestamp": 0.3}]}})";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(RunFolderTest, RunDataHoldsEveryOutputAndDecimatesTheDenseMapToTheBudget) {
  RunDataOptions options;
  options.dense_budget = 100;
  options.ground_truth = (dir_ / "truth.txt").string();
  const nlohmann::json data = LoadRunData(dir_.string(), options);
  EXPECT_EQ(data["mode"], "view");
  EXPECT_EQ(data["trajectory"].size(), 5u);
  EXPECT_EQ(data["trajectory"][2][0].get<double>(), 0.2);
  EXPECT_EQ(data["trajectory"][2][1].get<double>(), 0.2);
  EXPECT_EQ(data["keyframes"].size(), 2u);
  EXPECT_EQ(data["sparse"]["count"], 7);
  EXPECT_EQ(data["dense"]["count"], 100);
  EXPECT_EQ(data["dense"]["total"], 1000);
  // 100 points of xyz float32: 1200 bytes, 1600 base64 characters.
  EXPECT_EQ(data["dense"]["positions"].get<std::string>().size(), 1600u);
  EXPECT_EQ(data["loops"].size(), 1u);
  EXPECT_EQ(data["stats"]["frames"], 5);
  // Aligned into the estimate's frame, the shifted ground truth lies on the estimate.
  ASSERT_EQ(data["ground_truth"].size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(data["ground_truth"][i][1].get<double>(), 0.1 * i, 1e-9);
    EXPECT_NEAR(data["ground_truth"][i][2].get<double>(), 0.02 * i * i, 1e-9);
  }
  ASSERT_EQ(data["errors"].size(), 5u);
  EXPECT_NEAR(data["ate"]["rmse"].get<double>(), 0.0, 1e-9);
}

TEST_F(RunFolderTest, GroundTruthIsFoundBesideTheDatasetThatStatsNames) {
  fs::create_directories(dir_ / "sequence");
  fs::copy_file(dir_ / "truth.txt", dir_ / "sequence" / "groundtruth.txt");
  std::ofstream stats(dir_ / "stats.json");
  stats << nlohmann::json({{"dataset", (dir_ / "sequence").string()}}).dump();
  stats.close();
  const nlohmann::json data = LoadRunData(dir_.string(), RunDataOptions());
  EXPECT_EQ(data["ground_truth"].size(), 5u);
  EXPECT_EQ(data["ate"]["file"], (dir_ / "sequence" / "groundtruth.txt").string());
}

TEST_F(RunFolderTest, FrameLogEventsComeWithTheRunAndItsAbsenceIsNoted) {
  EXPECT_EQ(LoadRunData(dir_.string(), RunDataOptions()).count("events"), 0u);
  {
    std::ofstream log(dir_ / "frames.tsv");
    log << "frame\ttimestamp\twall_s\ttracked\tkeyframe\tmovers_share\n"
        << "0\t0.0\t5.0\t1\t1\t0.25\n"
        << "3\t0.1\t5.1\t0\t0\t0.5\n";
  }
  const nlohmann::json data = LoadRunData(dir_.string(), RunDataOptions());
  const nlohmann::json& events = data["events"];
  EXPECT_EQ(events["frame"], nlohmann::json::array({0, 3}));
  EXPECT_EQ(events["tracked"], nlohmann::json::array({1, 0}));
  EXPECT_EQ(events["keyframe"], nlohmann::json::array({1, 0}));
  EXPECT_DOUBLE_EQ(events["movers_share"][1].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(events["timestamp"][1].get<double>(), 0.1);
  // Only the columns the page draws travel; those the log lacks are absent.
  EXPECT_EQ(events.count("wall_s"), 0u);
  EXPECT_EQ(events.count("removed"), 0u);
  for (const auto& note : data["notes"]) {
    EXPECT_EQ(note.get<std::string>().find("frames.tsv"), std::string::npos) << note;
  }
}

TEST_F(RunFolderTest, ABrokenFrameLogIsAnErrorNamingTheFileAndLine) {
  const std::string path = (dir_ / "frames.tsv").string();
  const auto expect_error = [&](const std::string& text, const std::string& expected) {
    std::ofstream(path) << text;
    try {
      LoadRunData(dir_.string(), RunDataOptions());
      ADD_FAILURE() << "no error for: " << text;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
    }
  };
  expect_error("frame\ttimestamp\n0\t0.0\n", "no 'tracked' column");
  expect_error("frame\ttimestamp\ttracked\n0\t0.0\t1\n1\t0.1\n", "line 3: 2 fields");
  expect_error("frame\ttimestamp\ttracked\n0\tnoon\t1\n", "line 2: 'noon' is not a number");
  expect_error("", "empty");
}

TEST_F(RunFolderTest, MissingOutputsAreNamed) {
  fs::remove(dir_ / "stats.json");
  EXPECT_EQ(MissingRunFiles(dir_.string()), std::vector<std::string>{"stats.json"});
  fs::remove(dir_ / "CameraTrajectory.txt");
  try {
    LoadRunData(dir_.string(), RunDataOptions());
    FAIL() << "no error for a folder without outputs";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(dir_.string()), std::string::npos) << message;
    EXPECT_NE(message.find("missing CameraTrajectory.txt, stats.json"), std::string::npos)
        << message;
  }
  EXPECT_THROW(LoadRunData((dir_ / "nothing").string(), RunDataOptions()), Error);
}

TEST_F(RunFolderTest, OptionalOutputsMayBeAbsent) {
  fs::remove(dir_ / "dense_map.ply");
  fs::remove(dir_ / "sparse_map.ply");
  fs::remove(dir_ / "KeyFrameTrajectory.txt");
  const nlohmann::json data = LoadRunData(dir_.string(), RunDataOptions());
  EXPECT_EQ(data["trajectory"].size(), 5u);
  EXPECT_EQ(data["keyframes"].size(), 0u);
  EXPECT_FALSE(data.contains("dense"));
  EXPECT_FALSE(data.contains("ground_truth"));
  ASSERT_EQ(data["notes"].size(), 2u);
  EXPECT_NE(data["notes"][0].get<std::string>().find("sparse_map.ply"), std::string::npos);
  EXPECT_NE(data["notes"][1].get<std::string>().find("frames.tsv"), std::string::npos);
}

TEST_F(RunFolderTest, CliNamesTheMissingFilesAndExits2) {
  fs::remove(dir_ / "stats.json");
  for (const std::string command : {"view", "report"}) {
    const CliResult result = RunCli(command + " " + dir_.string());
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_NE(result.output.find("error: "), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("missing stats.json"), std::string::npos) << result.output;
  }
}

TEST_F(RunFolderTest, ReportIsOneFileWithTheDataInlined) {
  const fs::path report = dir_ / "report.html";
  const CliResult result = RunCli("report " + dir_.string() + " --out " + report.string());
  ASSERT_EQ(result.status, 0) << result.output;
  std::ifstream in(report);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("window.DRVSLAM_DATA = {"), std::string::npos);
  EXPECT_NE(html.find("\"mode\":\"report\""), std::string::npos);
  // Nothing to fetch: no script or stylesheet by URL.
  EXPECT_EQ(html.find("src=\""), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
}

TEST(ViewerPage, InlinedDataCannotCloseTheScriptElement) {
  const std::string hostile = "</script><script>alert(1)</script><!--";
  const std::string page = SelfContainedViewerPage({{"title", hostile}});
  const std::string served = ServedViewerPage();
  const auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
      ++n;
    }
    return n;
  };
  // Two script elements: the data and the bundle; the title's tags are escaped.
  EXPECT_EQ(count(page, "</script>"), 2u);
  EXPECT_NE(page.find("\\u003c/script>\\u003cscript>alert(1)"), std::string::npos);
  EXPECT_EQ(count(served, "<script src=\"viewer.js\"></script>"), 1u);
  EXPECT_EQ(served.find("<!--DRVSLAM_SCRIPT-->"), std::string::npos);
}

TEST(ViewerJson, Base64MatchesRfc4648) {
  EXPECT_EQ(Base64("", 0), "");
  EXPECT_EQ(Base64("f", 1), "Zg==");
  EXPECT_EQ(Base64("fo", 2), "Zm8=");
  EXPECT_EQ(Base64("foo", 3), "Zm9v");
  EXPECT_EQ(Base64("foobar", 6), "Zm9vYmFy");
  const unsigned char high[] = {0xff, 0xfe, 0x00};
  EXPECT_EQ(Base64(high, 3), "//4A");
}

TEST(ViewerJson, DecimationKeepsEvenlySpacedPoints) {
  DenseCloud cloud(10);
  for (int i = 0; i < 10; ++i) cloud[i].position.x() = static_cast<float>(i);
  const DenseCloud kept = Decimate(cloud, 3);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[0].position.x(), 0.0f);
  EXPECT_EQ(kept[1].position.x(), 3.0f);
  EXPECT_EQ(kept[2].position.x(), 6.0f);
  EXPECT_EQ(Decimate(cloud, 10).size(), 10u);
  EXPECT_EQ(Decimate(cloud, 0).size(), 0u);
}

TEST(ViewerJson, TruthOverlayUndoesARotatedAndShiftedFrame) {
  // The ground truth's frame: the estimate's turned 90 degrees about z and moved.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d shift(2.0, -1.0, 0.5);
  Trajectory estimate, truth;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d p(std::cos(0.3 * i), 0.1 * i, std::sin(0.2 * i));
    estimate.push_back({0.05 * i, SE3(Eigen::Quaterniond::Identity(), p)});
    truth.push_back({0.05 * i, SE3(Eigen::Quaterniond::Identity(), turn * p + shift)});
  }
  std::string why;
  const std::optional<TruthOverlay> overlay = OverlayTruth(truth, estimate, &why);
  ASSERT_TRUE(overlay) << why;
  EXPECT_EQ(overlay->matched, 20u);
  for (int i = 0; i < 20; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(overlay->ground_truth[i][1 + axis].get<double>(),
                  estimate[i].T_wc.Translation()[axis], 1e-9);
    }
  }
  EXPECT_NEAR(overlay->rmse, 0.0, 1e-9);
  // Stamps that never associate: no overlay, and why.
  Trajectory late = truth;
  for (StampedPose& pose : late) pose.timestamp += 100.0;
  EXPECT_FALSE(OverlayTruth(late, estimate, &why));
  EXPECT_FALSE(why.empty());
}

TEST(WebServer, AnswersHttpFromItsHandlerAnd404Otherwise) {
  WebServer server(0, [](const std::string& path) -> std::optional<HttpResponse> {
    if (path == "/hello") return HttpResponse{200, "text/plain", "hello there"};
    return std::nullopt;
  });
  ASSERT_GT(server.Port(), 0);
  const std::string hello = HttpGet(server.Port(), "/hello?x=1");
  EXPECT_NE(hello.find("200"), std::string::npos) << hello;
  EXPECT_NE(hello.find("hello there"), std::string::npos) << hello;
  const std::string missing = HttpGet(server.Port(), "/nothing");
  EXPECT_NE(missing.find("404"), std::string::npos) << missing;
}

TEST(WebServer, PortInUseIsAnErrorNamingThePort) {
  const WebServer first(0, [](const std::string&) { return std::nullopt; });
  try {
    const WebServer second(first.Port(), [](const std::string&) { return std::nullopt; });
    FAIL() << "a second server listened on port " << first.Port();
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("port " + std::to_string(first.Port()) + " is in use"),
              std::string::npos)
        << message;
  }
  EXPECT_THROW(WebServer(70000, [](const std::string&) { return std::nullopt; }), Error);
}

TEST_F(RunFolderTest, CliPortInUseExits2) {
  const WebServer taken(0, [](const std::string&) { return std::nullopt; });
  const std::string port = std::to_string(taken.Port());
  const CliResult view = RunCli("view " + dir_.string() + " --port " + port);
  EXPECT_EQ(view.status, 2) << view.output;
  EXPECT_NE(view.output.find("error: port " + port + " is in use"), std::string::npos)
      << view.output;
  // The live viewer refuses before tracking anything.
  const fs::path sequence = dir_ / "sequence";
  const CliResult synth =
      RunCli("--log-level warn synth --scenario static_xyz --frames 3 --out " + sequence.string());
  ASSERT_EQ(synth.status, 0) << synth.output;
  const CliResult run = RunCli("run --dataset " + sequence.string() + " --out " +
                               (dir_ / "out").string() + " --viewer " + port);
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("error: port " + port + " is in use"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "CameraTrajectory.txt"));
}

}  // namespace
}  // namespace drvslam
