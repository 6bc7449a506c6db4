// adahrs fit --run DIR [--run DIR ...] [--strategy FILE] --out DIR: fits every IMU of the runs
// (a thermal-calibration run and a sensor-calibration run) with the strategy (default: the joint
// strategy for firmware format 3, what the campaign downloads) and writes OUT/<serial>.json per
// unit, as the campaign does.
// adahrs fit --run DIR --ads-strategy NAME --out DIR: fits every ADS unit of one ADS calibration
// run with the ADS strategy NAME (reference, tolerance_minimax, pressure_minimax,
// hysteresis_compensated) and writes
// OUT/<serial>.json per unit, as the demo campaign does (docs/constants-file.md,
// docs/calibration-strategies.md).
// adahrs fit --run DIR --stage thermal|sensor|cross_axis [--base DIR] --out DIR: one stage of the
// staged process with the reference strategy (docs/campaign.md "The staged process"); past the
// thermal stage the units' own compensated rows are checked against the model of the base's
// constants (OUT/mode_conformance.json).
// adahrs fit --replay DIR [--strategy FILE]: runs each external strategy fit of DIR again on its
// kept request and compares the constants (docs/strategies-external.md "Replaying a fit").
#include <algorithm>
#include <array>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/campaign/campaign_fits.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "calib/imu_calibration/external_replay.h"
#include "calib/imu_calibration/imu_strategy.h"
#include "calib/imu_calibration/mode_conformance.h"
#include "common/printable_text.h"

namespace adahrs::apps {

namespace {

// What a staged fit holds and what it leaves for the later stages.
std::string StageNote(calib::ImuStage stage) {
  switch (stage) {
    case calib::ImuStage::kThermal:
      return ", thermal stage (sensor and cross-axis constants left at their defaults)";
    case calib::ImuStage::kSensor:
      return ", sensor stage on the base's thermal constants (cross-axis left the identity)";
    case calib::ImuStage::kCrossAxis:
      return ", cross-axis stage on the base's thermal and sensor constants";
  }
  return "";
}

// ADS: one calibration run fitted with the named strategy.
void FitAds(const std::vector<std::string>& runs,
            const std::string& strategy,
            const std::string& out) {
  if (runs.size() != 1) {
    throw CLI::ValidationError("--ads-strategy",
                               "takes exactly one --run (an ADS calibration run)");
  }
  const auto written = calib::FitAdsIntoDirectory(runs.front(), strategy, out, ADAHRS_VERSION);
  if (written.empty())
    throw std::runtime_error(runs.front() + "/meta.json: the run has no ADS unit");
  for (const calib::WrittenConstants& w : written) {
    std::cout << fmt::format(
        "{}: strategy {} -> {}\n", w.file.serial, w.file.strategy, w.path.string());
  }
}

// The units of comp0-2, comp3-5 and comp6-8 in each compensated mode (docs/recording-format.md).
std::array<const char*, 3> ModeUnits(int mode) {
  switch (mode) {
    case 1:
      return {"duty", "duty", "counts"};
    case 2:
      return {"g", "g", "deg/s"};
    default:
      return {"m/s^2", "deg/s", "g"};
  }
}

// The largest |unit - model| of each group of three outputs, with the mode's units.
std::string WorstByGroup(const calib::ModeConformance& m) {
  const std::array<const char*, 3> units = ModeUnits(m.mode);
  std::string worst;
  for (size_t group = 0; group < 3; ++group) {
    double max_abs = 0.0;
    for (size_t i = 3 * group; i < 3 * group + 3; ++i)
      max_abs = std::max(max_abs, m.channels[i].max_abs_diff);
    worst += fmt::format("{}comp{}-{} {:.3g} {}",
                         group == 0 ? "" : ", ",
                         3 * group,
                         3 * group + 2,
                         max_abs,
                         units[group]);
  }
  return worst;
}

// Staged process: the runs were made with the base's constants in the units (those of the units
// just fitted), so the units' own compensated output is checked against the pipeline's model of
// it; printed per unit and written to OUT/mode_conformance.json.
void CheckBaseConformance(const std::vector<std::filesystem::path>& runs,
                          const calib::ImuStageRequest& staged,
                          const std::vector<calib::WrittenConstants>& fitted,
                          const std::filesystem::path& out) {
  std::map<std::string, firmware_model::ImuCalibrationConstants> held;
  for (const calib::WrittenConstants& w : fitted) {
    held[w.file.serial] = *calib::ReadStageBase(w.file.serial, staged).imu;
  }
  std::vector<calib::RunConformance> results;
  for (const std::filesystem::path& run : runs) {
    results.push_back({run, calib::CheckModeConformance(run, held)});
    for (const calib::ModeConformance& m : results.back().units) {
      std::cout << fmt::format(
          "{}: mode-{} output of {} rows against the model of the base's constants, largest "
          "|unit - model|: {}{}\n",
          m.serial,
          m.mode,
          m.rows,
          WorstByGroup(m),
          m.flagged_rows ? fmt::format(" ({} flagged rows not compared)", m.flagged_rows) : "");
    }
  }
  calib::WriteModeConformance(out / "mode_conformance.json", results);
}

// Replays the external fits of `dir`; exits 1 when a unit's constants differ.
void ReplayFits(const std::string& dir, const std::string& strategy_file) {
  std::optional<std::filesystem::path> strategy;
  if (!strategy_file.empty()) strategy = strategy_file;
  bool all_identical = true;
  for (const calib::ExternalReplayOutcome& o : calib::ReplayExternalFits(dir, strategy)) {
    std::cout << fmt::format("{}: {} ({} s){}{}\n",
                             o.serial,
                             o.constants_identical ? "constants reproduced bit for bit"
                                                   : "constants differ: " + o.difference,
                             fmt::format("{:.1f}", o.elapsed_s),
                             o.reply_identical ? ", reply byte-identical" : ", reply bytes differ",
                             o.strategy_unchanged ? ""
                                                  : "; the strategy file is not the one "
                                                    "recorded (its SHA-256 differs)");
    all_identical = all_identical && o.constants_identical;
  }
  if (!all_identical) throw CLI::RuntimeError(1);
}

}  // namespace

void RegisterFitCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("fit", "Fit calibration constants from recordings");
  auto runs = std::make_shared<std::vector<std::string>>();
  auto strategy_file = std::make_shared<std::string>();
  auto ads_strategy = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("--run", *runs, "Run directory (repeat for several)");
  CLI::Option* imu_option =
      cmd->add_option("--strategy",
                      *strategy_file,
                      "IMU strategy file (default: joint, firmware format 3, auto order)");
  cmd->add_option("--ads-strategy",
                  *ads_strategy,
                  "Fit the ADS units of one ADS calibration run with this strategy: reference, "
                  "tolerance_minimax, pressure_minimax or hysteresis_compensated")
      ->excludes(imu_option);
  cmd->add_option("--out", *out, "Output directory for the constants files");
  auto replay = std::make_shared<std::string>();
  cmd->add_option("--replay",
                  *replay,
                  "Run the external strategy fits of this fit directory again on their kept "
                  "requests and compare the constants (writes nothing)")
      ->excludes("--run")
      ->excludes("--out")
      ->excludes("--ads-strategy");
  auto stage = std::make_shared<std::string>();
  auto base = std::make_shared<std::string>();
  cmd->add_option("--stage",
                  *stage,
                  "Staged process: fit this stage alone with the reference strategy: thermal, "
                  "sensor (on the base's thermal constants) or cross_axis (on its thermal and "
                  "sensor constants)")
      ->check(CLI::IsMember({"thermal", "sensor", "cross_axis"}))
      ->excludes("--ads-strategy");
  cmd->add_option("--base",
                  *base,
                  "Staged process: the previous stage's --out directory (<serial>.json per unit)");
  cmd->callback([runs, strategy_file, ads_strategy, out, stage, base, replay] {
    if (!replay->empty()) {
      ReplayFits(*replay, *strategy_file);
      return;
    }
    if (runs->empty()) throw CLI::RequiredError("--run");
    if (out->empty()) throw CLI::RequiredError("--out");
    if (!ads_strategy->empty()) {
      FitAds(*runs, *ads_strategy, *out);
      return;
    }
    std::optional<calib::ImuStageRequest> staged;
    if (!stage->empty()) {
      staged = calib::ImuStageRequest{*calib::ParseImuStage(*stage), *base};
      if ((staged->stage == calib::ImuStage::kThermal) != base->empty()) {
        throw CLI::ValidationError("--base",
                                   staged->stage == calib::ImuStage::kThermal
                                       ? "the thermal stage is the first: it takes no base"
                                       : "the " + *stage +
                                             " stage needs the previous stage's "
                                             "constants directory");
      }
    } else if (!base->empty()) {
      throw CLI::ValidationError("--base", "only with --stage sensor or --stage cross_axis");
    }
    // The staged process is the reference method's; without a stage the default is the joint
    // strategy's format 3, what the campaign downloads.
    const calib::ImuStrategy strategy = !strategy_file->empty()
                                            ? calib::ImuStrategy::Load(*strategy_file)
                                        : staged ? calib::ImuStrategy::Reference()
                                                 : calib::ImuStrategy::JointFormat3();
    const std::vector<std::filesystem::path> dirs(runs->begin(), runs->end());
    const std::vector<calib::WrittenConstants> fitted =
        calib::FitImuIntoDirectory(dirs, strategy, *out, ADAHRS_VERSION, staged);
    for (const calib::WrittenConstants& w : fitted) {
      std::cout << fmt::format(
          "{}: strategy {}{}, {} excluded rows -> {}\n",
          w.file.serial,
          w.file.strategy,
          staged ? StageNote(staged->stage) : "",
          w.file.imu_diagnostics ? w.file.imu_diagnostics->excluded_rows.value_or(0) : 0,
          w.path.string());
      for (const std::string& line : w.log) {
        std::cout << fmt::format(
            "{}: {}: {}\n", w.file.serial, w.file.strategy, common::PrintableText(line));
      }
    }
    if (staged && staged->stage != calib::ImuStage::kThermal) {
      CheckBaseConformance(dirs, *staged, fitted, *out);
    }
  });
}

}  // namespace adahrs::apps
