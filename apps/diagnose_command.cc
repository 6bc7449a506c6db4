// adahrs diagnose (--run DIR [--run DIR...] [--unit SERIAL] | --csv SIDECAR...) [--profile nominal]
// [--model UNIT.json] --out DIR: where the recordings and the pipeline's model part ways, which
// physics the model leaves out, the held-out fit with it (calib/diagnosis, docs/diagnose.md), and
// with --model the unit file with the findings switched on (OUT/model.json). Exit 0 whatever is
// found; 1 on bad input.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/campaign/augmented_model.h"
#include "calib/diagnosis/diagnosis_output.h"

namespace adahrs::apps {

void RegisterDiagnoseCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("diagnose", "Locate and name the physics a recording shows and the model leaves out");
  auto runs = std::make_shared<std::vector<std::string>>();
  auto csvs = std::make_shared<std::vector<std::string>>();
  auto unit = std::make_shared<std::string>();
  auto profile = std::make_shared<std::string>("nominal");
  auto model = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  CLI::Option* run_opt = cmd->add_option("--run", *runs, "run directory (repeatable: the runs of one batch)");
  CLI::Option* csv_opt =
      cmd->add_option("--csv", *csvs, "generic channel recording: its JSON sidecar (repeatable; docs/diagnose.md)");
  run_opt->excludes(csv_opt);
  csv_opt->excludes(run_opt);
  cmd->add_option("--unit", *unit, "diagnose only this unit (IMU or ADS serial)");
  cmd->add_option("--profile", *profile, "the model to compare with: nominal (the pipeline's forward model)")
      ->check(CLI::IsMember({"nominal"}));
  cmd->add_option("--model", *model,
                  "unit file of the rig's truth schema: write OUT/model.json, it with the findings switched on");
  cmd->add_option("--out", *out, "output directory (diagnosis.json, report.html)")->required();
  cmd->callback([runs, csvs, unit, model, out] {
    if (runs->empty() && csvs->empty()) throw std::runtime_error("diagnose: give --run DIR or --csv SIDECAR.json");
    std::vector<std::filesystem::path> dirs(runs->begin(), runs->end());
    std::vector<std::filesystem::path> sidecars(csvs->begin(), csvs->end());
    const calib::DiagnosisRun run =
        sidecars.empty() ? calib::DiagnoseRuns(dirs, unit->empty() ? std::nullopt : std::optional<std::string>(*unit))
                         : calib::DiagnoseChannelFiles(sidecars);
    calib::WriteDiagnosis(run, *out);
    for (const calib::UnitDiagnosis& u : run.units) {
      std::cout << fmt::format("{}: {} finding(s), {} unexplained\n", u.serial, u.findings.size(), u.unexplained.size());
      for (const calib::Finding& f : u.findings) std::cout << "  " << f.words << "\n";
      for (const calib::Unexplained& x : u.unexplained) std::cout << "  unexplained: " << x.channel << " " << x.where << ": " << x.description << "\n";
      if (u.findings.empty() && u.unexplained.empty()) std::cout << "  no missing physics found\n";
    }
    std::cout << "wrote " << (std::filesystem::path(*out) / "diagnosis.json").string() << " and report.html\n";
    if (!model->empty()) {
      const calib::AugmentedModel m = calib::WriteAugmentedModel(run, *model, *out);
      for (const std::string& a : m.applied) std::cout << "  model: " << a << "\n";
      for (const std::string& n : m.not_applied) std::cout << "  model, not applied: " << n << "\n";
      std::cout << "wrote " << (std::filesystem::path(*out) / "model.json").string() << "\n";
    }
  });
}

}  // namespace adahrs::apps
