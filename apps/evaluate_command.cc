// adahrs evaluate --constants FILE --truth FILE [--out FILE]: truth evaluation of a simulated
// unit's constants, IMU (proving/evaluation/imu_evaluation.h) or ADS
// (proving/evaluation/ads_evaluation_report.h) by the constants file's kind; prints the worst
// errors and verdicts and writes evaluation.json (default: beside the constants).
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "common/atomic_file.h"
#include "proving/evaluation/ads_evaluation_report.h"
#include "proving/evaluation/imu_evaluation.h"
#include "proving/evaluation/truth_file.h"

namespace adahrs::apps {
namespace {

// Writes the document and returns the line to print.
std::string EvaluateImuFile(const calib::ConstantsFile& file,
                            const proving::TruthFile& truth,
                            const std::string& path) {
  proving::ImuEvaluationOptions options;
  if (file.imu_diagnostics && file.imu_diagnostics->local_gravity_mps2) {
    options.g_local_mps2 = *file.imu_diagnostics->local_gravity_mps2;
  }
  const proving::ImuEvaluation e = proving::EvaluateImu(
      file, proving::ImuTruth(truth, file.serial), calib::Specification::Reference(), options);
  common::WriteFileAtomically(path, e.report.dump(2) + "\n");
  return fmt::format(
      "{}: acceleration worst {:.3f} mg ({}), body rate worst {:.4f} deg/s ({}) -> {}\n",
      file.serial,
      e.worst_accel_mg,
      e.accel_verdict,
      e.worst_rate_dps,
      e.rate_verdict,
      path);
}

std::string EvaluateAdsFile(const calib::ConstantsFile& file,
                            const proving::TruthFile& truth,
                            const std::string& path) {
  const proving::AdsFileEvaluation e =
      proving::EvaluateAds(file, proving::AdsTruth(truth, file.serial));
  common::WriteFileAtomically(path, e.report.dump(2) + "\n");
  return fmt::format(
      "{}: altitude worst {:.3f} x tolerance ({}), airspeed worst {:.3f} x tolerance ({}) -> {}\n",
      file.serial,
      e.evaluation.altitude.worst_ratio_no_history,
      e.altitude_verdict,
      e.evaluation.airspeed.worst_ratio_no_history,
      e.airspeed_verdict,
      path);
}

}  // namespace

void RegisterEvaluateCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "evaluate", "Evaluate IMU or ADS constants against a simulated unit's truth");
  auto constants = std::make_shared<std::string>();
  auto truth = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("--constants", *constants, "constants.json")->required();
  cmd->add_option("--truth", *truth, "truth/<serial>.json of the simulated unit")->required();
  cmd->add_option("--out", *out, "evaluation.json (default: <constants>.evaluation.json)");
  cmd->callback([constants, truth, out] {
    const calib::ConstantsFile file = calib::ReadConstantsFile(*constants);
    const proving::TruthFile truth_file = proving::ReadTruthFile(*truth);
    const std::string path = out->empty() ? *constants + ".evaluation.json" : *out;
    std::cout << (file.kind == hil::UnitKind::kAds ? EvaluateAdsFile(file, truth_file, path)
                                                   : EvaluateImuFile(file, truth_file, path));
  });
}

}  // namespace adahrs::apps
