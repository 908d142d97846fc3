#include "drvslam/tools/eval/eval_report.h"

#include <cstdarg>
#include <cstdio>
#include <fstream>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

std::string Printf(const char* format, ...) __attribute__((format(printf, 1, 2)));

std::string Printf(const char* format, ...) {
  char buffer[256];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  return buffer;
}

std::string MetresRow(const char* name, double metres) {
  return Printf("  %-22s %12.6f m %10.3f cm\n", name, metres, 100.0 * metres);
}

}  // namespace

nlohmann::json EvalReportJson(const AteResult& ate, const std::optional<RpeResult>& rpe) {
  nlohmann::json json;
  json["ate"] = {{"rmse", ate.errors.rmse},
                 {"mean", ate.errors.mean},
                 {"median", ate.errors.median},
                 {"std", ate.errors.std},
                 {"min", ate.errors.min},
                 {"max", ate.errors.max},
                 {"matched", ate.matched},
                 {"coverage", ate.coverage},
                 {"coverage_of", CoverageOfName(ate.coverage_of)},
                 {"scale", ate.alignment.scale}};
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    rotation.push_back({ate.alignment.R(r, 0), ate.alignment.R(r, 1), ate.alignment.R(r, 2)});
  }
  json["alignment"] = {
      {"rotation", rotation},
      {"translation", {ate.alignment.t.x(), ate.alignment.t.y(), ate.alignment.t.z()}},
      {"scale", ate.alignment.scale},
      {"fitted", ate.fitted}};
  if (rpe) {
    json["rpe"] = {{"trans_rmse", rpe->trans_rmse}, {"rot_rmse_deg", rpe->rot_rmse_deg},
                   {"trans_mean", rpe->trans_mean}, {"rot_mean_deg", rpe->rot_mean_deg},
                   {"pairs", rpe->pairs},           {"delta", rpe->delta}};
  } else {
    json["rpe"] = nullptr;
  }
  return json;
}

void WriteEvalReportJson(const std::string& path, const AteResult& ate,
                         const std::optional<RpeResult>& rpe) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open the --json file for writing");
  out << EvalReportJson(ate, rpe).dump(2) << "\n";
  out.flush();
  if (!out) throw Error(path + ": writing the --json file failed");
}

Alignment ReadEvalAlignment(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the --alignment-from file");
  try {
    const nlohmann::json json = nlohmann::json::parse(in);
    const nlohmann::json& a = json.at("alignment");
    Alignment alignment;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) alignment.R(r, c) = a.at("rotation").at(r).at(c).get<double>();
      alignment.t[r] = a.at("translation").at(r).get<double>();
    }
    alignment.scale = a.at("scale").get<double>();
    const double orthogonality =
        (alignment.R * alignment.R.transpose() - Eigen::Matrix3d::Identity()).norm();
    if (!alignment.R.allFinite() || orthogonality > 1e-6 || alignment.R.determinant() < 0 ||
        !alignment.t.allFinite() || !(alignment.scale > 0)) {
      throw Error(path + ": alignment is not a rotation, translation and positive scale");
    }
    return alignment;
  } catch (const nlohmann::json::exception& error) {
    throw Error(path + ": no alignment (a drvslam eval --json file): " + error.what());
  }
}

std::string FormatEvalTable(const AteResult& ate, const std::optional<RpeResult>& rpe) {
  std::string table;
  if (ate.fitted) {
    table += Printf("Absolute trajectory error (%s alignment, scale %.6f)\n",
                    ate.with_scale ? "similarity" : "rigid", ate.alignment.scale);
  } else {
    table += Printf("Absolute trajectory error (given alignment, not fitted; scale %.6f)\n",
                    ate.alignment.scale);
  }
  table += MetresRow("rmse", ate.errors.rmse);
  table += MetresRow("mean", ate.errors.mean);
  table += MetresRow("median", ate.errors.median);
  table += MetresRow("std", ate.errors.std);
  table += MetresRow("min", ate.errors.min);
  table += MetresRow("max", ate.errors.max);
  table += Printf("  %-22s %12zu\n", "matched poses", ate.matched);
  table += Printf("  %-22s %12.2f %%  (%s)\n", "coverage", 100.0 * ate.coverage,
                  ate.coverage_of == CoverageOf::kSequenceFrames ? "of the sequence's frames"
                                                                 : "of ground-truth poses");
  if (!rpe) {
    table += "Relative pose error: n/a (too short: fewer than 2 pose pairs)\n";
    return table;
  }
  table += Printf("Relative pose error (delta %.3f s)\n", rpe->delta);
  table += MetresRow("translation rmse", rpe->trans_rmse);
  table += MetresRow("translation mean", rpe->trans_mean);
  table += Printf("  %-22s %12.6f deg\n", "rotation rmse", rpe->rot_rmse_deg);
  table += Printf("  %-22s %12.6f deg\n", "rotation mean", rpe->rot_mean_deg);
  table += Printf("  %-22s %12zu\n", "pose pairs", rpe->pairs);
  return table;
}

}  // namespace drvslam
