#include "drvslam/tools/eval/eval_report.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <set>

#include "drvslam/core/error.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

AteResult SomeAte() {
  AteResult ate;
  ate.errors.rmse = 0.0123;
  ate.errors.mean = 0.011;
  ate.errors.median = 0.01;
  ate.errors.std = 0.004;
  ate.errors.min = 0.001;
  ate.errors.max = 0.05;
  ate.matched = 798;
  ate.coverage = 0.97;
  return ate;
}

RpeResult SomeRpe() {
  RpeResult rpe;
  rpe.trans_rmse = 0.021;
  rpe.rot_rmse_deg = 0.6;
  rpe.trans_mean = 0.018;
  rpe.rot_mean_deg = 0.5;
  rpe.pairs = 760;
  rpe.delta = 1.0;
  return rpe;
}

std::set<std::string> Keys(const nlohmann::json& object) {
  std::set<std::string> keys;
  for (auto it = object.begin(); it != object.end(); ++it) keys.insert(it.key());
  return keys;
}

TEST(EvalReportTest, JsonHasExactlyTheContractKeys) {
  const nlohmann::json json = EvalReportJson(SomeAte(), SomeRpe());
  EXPECT_EQ(Keys(json), (std::set<std::string>{"ate", "alignment", "rpe"}));
  EXPECT_EQ(Keys(json["alignment"]),
            (std::set<std::string>{"rotation", "translation", "scale", "fitted"}));
  EXPECT_EQ(Keys(json["ate"]),
            (std::set<std::string>{"rmse", "mean", "median", "std", "min", "max", "matched",
                                   "coverage", "coverage_of", "scale"}));
  EXPECT_EQ(Keys(json["rpe"]), (std::set<std::string>{"trans_rmse", "rot_rmse_deg", "trans_mean",
                                                      "rot_mean_deg", "pairs", "delta"}));
  EXPECT_DOUBLE_EQ(json["ate"]["rmse"].get<double>(), 0.0123);
  EXPECT_EQ(json["ate"]["matched"].get<int>(), 798);
  EXPECT_DOUBLE_EQ(json["ate"]["scale"].get<double>(), 1.0);
  EXPECT_EQ(json["rpe"]["pairs"].get<int>(), 760);
  EXPECT_DOUBLE_EQ(json["rpe"]["rot_rmse_deg"].get<double>(), 0.6);
}

TEST(EvalReportTest, AlignmentReadsBackForAlignmentFrom) {
  AteResult ate = SomeAte();
  ate.alignment.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  ate.alignment.t = Eigen::Vector3d(0.5, -1.25, 2.0);
  const std::filesystem::path path =
      testing::ProcessTempFolder() / "drvslam_eval_alignment_test.json";
  WriteEvalReportJson(path.string(), ate, SomeRpe());
  const Alignment read = ReadEvalAlignment(path.string());
  EXPECT_LT((read.R - ate.alignment.R).norm(), 1e-12);
  EXPECT_EQ(read.t, ate.alignment.t);
  EXPECT_DOUBLE_EQ(read.scale, 1.0);
  // A file without an alignment is an error naming it.
  {
    std::ofstream out(path);
    out << R"({"ate": {}})";
  }
  try {
    ReadEvalAlignment(path.string());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ": no alignment"), std::string::npos);
  }
  std::filesystem::remove(path);
}

TEST(EvalReportTest, JsonFileRoundTripsAndBadPathIsAnError) {
  const std::filesystem::path path = testing::ProcessTempFolder() / "drvslam_eval_report_test.json";
  WriteEvalReportJson(path.string(), SomeAte(), SomeRpe());
  std::ifstream in(path);
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(json["rpe"]["trans_rmse"].get<double>(), 0.021);
  std::filesystem::remove(path);
  try {
    WriteEvalReportJson("/nonexistent-dir/report.json", SomeAte(), SomeRpe());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/report.json"), std::string::npos);
  }
}

TEST(EvalReportTest, TableShowsMetresCentimetresAndCounts) {
  const std::string table = FormatEvalTable(SomeAte(), SomeRpe());
  EXPECT_NE(table.find("0.012300 m"), std::string::npos) << table;
  EXPECT_NE(table.find("1.230 cm"), std::string::npos) << table;
  EXPECT_NE(table.find("798"), std::string::npos) << table;
  EXPECT_NE(table.find("97.00 %"), std::string::npos) << table;
  EXPECT_NE(table.find("0.600000 deg"), std::string::npos) << table;
  EXPECT_NE(table.find("rigid"), std::string::npos) << table;
}

TEST(EvalReportTest, CoverageSaysWhatItCountsAgainst) {
  AteResult ate = SomeAte();
  EXPECT_EQ(EvalReportJson(ate, SomeRpe())["ate"]["coverage_of"], "ground_truth_poses");
  EXPECT_NE(FormatEvalTable(ate, SomeRpe()).find("97.00 %  (of ground-truth poses)"),
            std::string::npos);
  ate.coverage_of = CoverageOf::kSequenceFrames;
  EXPECT_EQ(EvalReportJson(ate, SomeRpe())["ate"]["coverage_of"], "sequence_frames");
  EXPECT_NE(FormatEvalTable(ate, SomeRpe()).find("97.00 %  (of the sequence's frames)"),
            std::string::npos);
}

TEST(EvalReportTest, NoRpeIsNullAndNotAvailable) {
  const nlohmann::json json = EvalReportJson(SomeAte(), std::nullopt);
  EXPECT_TRUE(json["rpe"].is_null()) << json.dump();
  EXPECT_DOUBLE_EQ(json["ate"]["rmse"].get<double>(), 0.0123);
  const std::string table = FormatEvalTable(SomeAte(), std::nullopt);
  EXPECT_NE(table.find("Relative pose error: n/a"), std::string::npos) << table;
  EXPECT_EQ(table.find("pose pairs "), std::string::npos) << table;
}

}  // namespace
}  // namespace drvslam
