// adahrs fit --run DIR [--run DIR ...] [--strategy FILE] --out DIR: fits every IMU of the runs
// (a thermal-calibration run and a sensor-calibration run) with the strategy (default: the
// improved "joint" strategy) and writes OUT/<serial>.constants.json per unit
// (docs/constants-file.md, docs/calibration-strategies.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/imu_calibration/imu_strategy.h"

namespace adahrs::apps {

void RegisterFitCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("fit", "Fit calibration constants from recordings");
  auto runs = std::make_shared<std::vector<std::string>>();
  auto strategy_file = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("--run", *runs, "Run directory (repeat for several)")->required();
  cmd->add_option("--strategy", *strategy_file, "Strategy file (default: joint, auto order)");
  cmd->add_option("--out", *out, "Output directory for <serial>.constants.json")->required();
  cmd->callback([runs, strategy_file, out] {
    const calib::ImuStrategy strategy = strategy_file->empty()
                                            ? calib::ImuStrategy::Improved()
                                            : calib::ImuStrategy::Load(*strategy_file);
    const std::vector<std::filesystem::path> dirs(runs->begin(), runs->end());
    const auto files = calib::FitImuRuns(dirs, strategy, ADAHRS_VERSION);
    std::filesystem::create_directories(*out);
    for (const calib::ConstantsFile& f : files) {
      const auto path = std::filesystem::path(*out) / (f.serial + ".constants.json");
      calib::WriteConstantsFile(path, f);
      std::cout << fmt::format("{}: strategy {}, {} excluded rows -> {}\n", f.serial, f.strategy,
                               f.diagnostics.value("excluded_rows", 0), path.string());
    }
  });
}

}  // namespace adahrs::apps
