// adahrs acceptance --run DIR [--specification FILE] [--out DIR] [--db FILE]
// [--since-calibration-h H]: judges an acceptance run against a specification file (default: the
// AHR150A -A file compiled in; calib/acceptance/, docs/acceptance.md), and its rate points against
// the physical limit of bias wander over H hours since calibration; writes
// <out>/<serial>/acceptance.json per unit (default out: DIR/acceptance), prints the table and, with
// --db, records every point in the production records. Exit code 0 when every point passes, 1 when
// any fails, 2 on bad input (or when the files or the records cannot be written: no verdict reached
// its destination).
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/acceptance/acceptance_file.h"
#include "calib/acceptance/acceptance_judge.h"
#include "calib/records/acceptance_records.h"
#include "calib/records/records_store.h"

namespace adahrs::apps {

namespace {
constexpr int kExitFail = 1;
constexpr int kExitBadInput = 2;
}  // namespace

void RegisterAcceptanceCommand(CLI::App& app) {
  CLI::App* cmd =
      app.add_subcommand("acceptance", "Judge an acceptance run against the specification");
  auto run = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto db = std::make_shared<std::string>();
  auto specification = std::make_shared<std::string>();
  auto options = std::make_shared<calib::AcceptanceOptions>();
  cmd->add_option("--run", *run, "Acceptance run directory (recording in a calibrated mode)")
      ->required();
  cmd->add_option(
      "--out", *out, "Output directory for <serial>/acceptance.json (default: RUN/acceptance)");
  cmd->add_option("--specification",
                  *specification,
                  "Specification file (calib/specifications/*.json; default: AHR150A -A, "
                  "calib/specifications/ahr150a-a.json as compiled in)");
  cmd->add_option("--db", *db, "Production records database to record the points in");
  cmd->add_option("--since-calibration-h",
                  options->since_calibration_h,
                  "Hours between the calibration and this run: the bias wander the rate points' "
                  "physical limit counts")
      ->capture_default_str()
      ->check(CLI::Range(0.0, calib::kMaxSinceCalibration_h));
  cmd->callback([run, out, db, specification, options] {
    calib::AcceptanceRun result;
    std::vector<std::filesystem::path> files;
    try {
      const calib::Specification spec = specification->empty()
                                            ? calib::Specification::Reference()
                                            : calib::ReadSpecificationFile(*specification);
      std::cout << fmt::format(
          "specification {} version {} (sha256 {})\n", spec.name, spec.version, spec.sha256);
      result = calib::JudgeAcceptance(*run, spec, *options);
      const std::filesystem::path out_dir =
          out->empty() ? std::filesystem::path(*run) / "acceptance" : std::filesystem::path(*out);
      files = calib::WriteAcceptanceFiles(result, spec, ADAHRS_VERSION, out_dir);
    } catch (const std::exception& e) {
      std::cerr << "adahrs acceptance: " << e.what() << "\n";
      throw CLI::RuntimeError(kExitBadInput);
    }
    std::cout << calib::AcceptanceText(result);
    for (const auto& file : files) std::cout << "wrote " << file.string() << "\n";
    if (!db->empty()) {
      try {
        calib::RecordsStore store(*db);
        for (const auto& file : files) {
          const calib::AcceptanceRecords records = calib::AcceptanceRecordsFromFile(file);
          const bool added = store.AddAcceptance(records.source_sha256, records.points);
          std::cout << fmt::format("{}: {} points {}\n",
                                   file.string(),
                                   records.points.size(),
                                   added ? "recorded" : "already recorded");
        }
      } catch (const std::exception& e) {
        std::cerr << "adahrs acceptance: " << e.what() << "\n";
        throw CLI::RuntimeError(kExitBadInput);
      }
    }
    std::cout << (result.pass() ? "acceptance: PASS\n" : "acceptance: FAIL\n");
    if (!result.pass()) throw CLI::RuntimeError(kExitFail);
  });
}

}  // namespace adahrs::apps
