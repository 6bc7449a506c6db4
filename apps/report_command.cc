// adahrs report --run DIR [--fit DIR] [--acceptance DIR] --out FILE: report.html of one run
// (calib/report/, docs/report.md).
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "apps/commands.h"
#include "calib/report/run_report.h"

namespace adahrs::apps {

void RegisterReportCommand(CLI::App& app) {
  CLI::App* report = app.add_subcommand("report", "Write report.html for a run");
  auto run = std::make_shared<std::string>();
  auto fit = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto acceptance = std::make_shared<std::string>();
  report->add_option("--run", *run, "Run directory (recording)")->required();
  report->add_option(
      "--fit", *fit, "Fit directory (constants.json files, acceptance.json, evaluation.json)");
  report->add_option(
      "--acceptance",
      *acceptance,
      "Acceptance directory (<serial>/acceptance.json; default: RUN/acceptance if it exists)");
  report->add_option("--out", *out, "Output HTML file")->required();
  report->callback([run, fit, out, acceptance] {
    const auto optional_path = [](const std::string& text) {
      return text.empty() ? std::nullopt : std::optional<std::filesystem::path>(text);
    };
    calib::WriteRunReport(*run, optional_path(*fit), *out, optional_path(*acceptance));
    std::cout << "wrote " << *out << "\n";
  });
}

}  // namespace adahrs::apps
