// adahrs evaluate --constants FILE --truth FILE [--out FILE]: truth evaluation of IMU constants
// of a simulated unit (proving/evaluation/imu_evaluation.h); prints the worst errors and verdicts
// and writes evaluation.json (default: beside the constants).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "proving/evaluation/imu_evaluation.h"
#include "proving/evaluation/truth_file.h"

namespace adahrs::apps {

void RegisterEvaluateCommand(CLI::App& app) {
  CLI::App* cmd =
      app.add_subcommand("evaluate", "Evaluate IMU constants against a simulated unit's truth");
  auto constants = std::make_shared<std::string>();
  auto truth = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("--constants", *constants, "constants.json")->required();
  cmd->add_option("--truth", *truth, "truth/<serial>.json of the simulated unit")->required();
  cmd->add_option("--out", *out, "evaluation.json (default: <constants>.evaluation.json)");
  cmd->callback([constants, truth, out] {
    const calib::ConstantsFile file = calib::ReadConstantsFile(*constants);
    const sensor_sim::ImuUnitParams params =
        proving::ImuTruth(proving::ReadTruthFile(*truth), file.serial);
    proving::ImuEvaluationOptions options;
    if (file.imu_diagnostics && file.imu_diagnostics->local_gravity_mps2) {
      options.g_local_mps2 = *file.imu_diagnostics->local_gravity_mps2;
    }
    const proving::ImuEvaluation e =
        proving::EvaluateImu(file, params, calib::Specification::Reference(), options);
    const std::string path = out->empty() ? *constants + ".evaluation.json" : *out;
    std::ofstream written(path);
    written << e.report.dump(2) << "\n";
    written.flush();
    if (!written) throw std::runtime_error(path + ": cannot write the evaluation");
    std::cout << fmt::format(
        "{}: acceleration worst {:.3f} mg ({}), body rate worst {:.4f} deg/s ({}) -> {}\n",
        file.serial,
        e.worst_accel_mg,
        e.accel_verdict,
        e.worst_rate_dps,
        e.rate_verdict,
        path);
  });
}

}  // namespace adahrs::apps
