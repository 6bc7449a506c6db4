// adahrs diagnose (--run DIR [--run DIR...] [--unit SERIAL] | --csv SIDECAR...) [--profile nominal]
// [--model UNIT.json] --out DIR: where the recordings and the pipeline's model part ways, which
// physics the model leaves out, the held-out fit with it (calib/diagnosis, docs/diagnose.md), and
// with --model the unit file with the findings switched on (OUT/model.json); with --check-run,
// that run re-simulated with the base and the augmented model and compared with its recording
// (OUT/replay_check.json, replay_check.html). Exit 0 whatever is found; 1 on bad input.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "apps/commands.h"
#include "diagnosis/diagnosis_output.h"
#include "diagnosis/replay_check_report.h"
#include "diagnosis/replay_comparison.h"
#include "proving/demo/augmented_model.h"
#include "rig_sim/recording_replay.h"

namespace adahrs::apps {
namespace {

void PrintReplayCheck(const diagnosis::ReplayComparison& c) {
  std::cout << fmt::format(
      "re-simulation of {} ({}): RMS of the acquisition means, recorded - replayed\n",
      c.recording.string(),
      c.held_out ? "held out: not a diagnosed run" : "a diagnosed run");
  for (const diagnosis::UnitReplayFit& u : c.units) {
    for (const diagnosis::ChannelReplayFit& ch : u.channels) {
      std::cout << fmt::format(
          "  {} {:<3} base model {:9.4g}  model.json {:9.4g}  noise alone {:9.4g} {} ({} "
          "acquisitions)\n",
          u.serial,
          ch.channel,
          ch.rms_base,
          ch.rms_model,
          ch.rms_noise,
          ch.unit,
          ch.acquisitions.size());
    }
  }
}

}  // namespace

void RegisterDiagnoseCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "diagnose", "Locate and name the physics a recording shows and the model leaves out");
  auto runs = std::make_shared<std::vector<std::string>>();
  auto csvs = std::make_shared<std::vector<std::string>>();
  auto unit = std::make_shared<std::string>();
  auto profile = std::make_shared<std::string>("nominal");
  auto model = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto check_runs = std::make_shared<std::vector<std::string>>();
  CLI::Option* run_opt =
      cmd->add_option("--run", *runs, "run directory (repeatable: the runs of one batch)");
  CLI::Option* csv_opt = cmd->add_option(
      "--csv", *csvs, "generic channel recording: its JSON sidecar (repeatable; docs/diagnose.md)");
  run_opt->excludes(csv_opt);
  csv_opt->excludes(run_opt);
  cmd->add_option("--unit", *unit, "diagnose only this unit (IMU or ADS serial)");
  cmd->add_option(
         "--profile", *profile, "the model to compare with: nominal (the pipeline's forward model)")
      ->check(CLI::IsMember({"nominal"}));
  cmd->add_option("--model",
                  *model,
                  "unit file of the rig's truth schema: write OUT/model.json, it with the findings "
                  "switched on");
  cmd->add_option(
         "--check-run",
         *check_runs,
         "with --model: re-simulate this run with the base file and with model.json and compare "
         "(repeatable; a run not diagnosed is a held-out check)")
      ->needs("--model");
  cmd->add_option("--out", *out, "output directory (diagnosis.json, report.html)")->required();
  cmd->callback([runs, csvs, unit, profile, model, out, check_runs] {
    if (runs->empty() && csvs->empty())
      throw std::runtime_error("diagnose: give --run DIR or --csv SIDECAR.json");
    std::vector<std::filesystem::path> dirs(runs->begin(), runs->end());
    std::vector<std::filesystem::path> sidecars(csvs->begin(), csvs->end());
    const diagnosis::DiagnosisRun run =
        sidecars.empty()
            ? diagnosis::DiagnoseRuns(
                  dirs, unit->empty() ? std::nullopt : std::optional<std::string>(*unit))
            : diagnosis::DiagnoseChannelFiles(sidecars);
    diagnosis::WriteDiagnosis(run, *out);
    if (sidecars.empty())
      std::cout << "compared with the " << *profile << " model: " << run.model << "\n";
    else
      std::cout << "compared with: " << run.model << " (--profile does not apply to --csv)\n";
    for (const std::string& n : run.notes) std::cout << "note: " << n << "\n";
    for (const diagnosis::UnitDiagnosis& u : run.units) {
      std::cout << fmt::format(
          "{}: {} finding(s), {} unexplained\n", u.serial, u.findings.size(), u.unexplained.size());
      for (const diagnosis::ChannelFitSummary& c : u.channels) {
        if (!c.bias_slope_per_c) continue;
        std::cout << fmt::format(
            "  {}: bias slope against temperature {:.4g} ± {:.2g} {}/degC (linear law); held-out "
            "RMS {:.3g} {} against {:.3g} of white noise\n",
            c.channel,
            *c.bias_slope_per_c,
            c.bias_slope_se_per_c.value_or(0.0),
            c.unit,
            c.held_out_rms_final,
            c.unit,
            c.white_noise_rms);
      }
      for (const diagnosis::Finding& f : u.findings) std::cout << "  " << f.words << "\n";
      for (const diagnosis::Unexplained& x : u.unexplained)
        std::cout << "  unexplained: " << x.channel << " " << x.where << ": " << x.description
                  << "\n";
      std::cout << "  verdict: " << u.Verdict() << "\n";
    }
    std::cout << "wrote " << (std::filesystem::path(*out) / "diagnosis.json").string()
              << " and report.html\n";
    if (!model->empty()) {
      const proving::AugmentedModel m = proving::WriteAugmentedModel(run, *model, *out);
      for (const std::string& a : m.applied) std::cout << "  model: " << a << "\n";
      for (const std::string& n : m.not_applied) std::cout << "  model, not applied: " << n << "\n";
      std::cout << "wrote " << (std::filesystem::path(*out) / "model.json").string() << "\n";
    }
    std::vector<diagnosis::ReplayComparison> checks;
    for (const std::string& check : *check_runs) {
      const std::filesystem::path dir(check);
      bool diagnosed = false;
      for (const std::string& r : *runs) diagnosed |= std::filesystem::equivalent(r, dir);
      const diagnosis::ReplayComparison c = diagnosis::CheckByReplay(
          dir,
          {*model},
          {std::filesystem::path(*out) / "model.json"},
          std::filesystem::path(*out) / "replay" / dir.filename(),
          !diagnosed,
          [](const std::filesystem::path& r,
             const std::vector<std::filesystem::path>& files,
             const std::filesystem::path& o) { rig_sim::ReplayRecording(r, files, o); });
      PrintReplayCheck(c);
      checks.push_back(c);
    }
    if (!check_runs->empty()) {
      diagnosis::WriteReplayCheck(checks, *out);
      std::cout << "wrote " << (std::filesystem::path(*out) / "replay_check.json").string()
                << " and replay_check.html\n";
    }
  });
}

}  // namespace adahrs::apps
