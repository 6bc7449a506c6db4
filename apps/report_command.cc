// adahrs report --run DIR [--fit DIR] [--acceptance DIR] --out FILE: report.html of one run
// (calib/report/, docs/report.md); with --certificate DIR [--operator NAME], also a certificate
// (HTML and PDF) per judged unit of the run, its constants taken from --fit when given.
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "calib/acceptance/acceptance_file.h"
#include "calib/report/certificate.h"
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
  auto certificates = std::make_shared<std::string>();
  auto operator_name = std::make_shared<std::string>();
  report->add_option("--certificate",
                     *certificates,
                     "Also write a certificate (<serial>.html, .pdf) per judged unit here");
  report->add_option("--operator", *operator_name, "Operator's name, on the certificates");
  auto specification = std::make_shared<std::string>();
  report->add_option("--specification",
                     *specification,
                     "Specification file the ADS error maps are drawn against (default: the "
                     "AHR150A -A, compiled in)");
  report->callback([run, fit, out, acceptance, certificates, operator_name, specification] {
    const auto optional_path = [](const std::string& text) {
      return text.empty() ? std::nullopt : std::optional<std::filesystem::path>(text);
    };
    const std::optional<calib::Specification> spec =
        specification->empty()
            ? std::nullopt
            : std::optional<calib::Specification>(calib::ReadSpecificationFile(*specification));
    calib::WriteRunReport(*run, optional_path(*fit), *out, optional_path(*acceptance), spec);
    std::cout << "wrote " << *out << "\n";
    if (certificates->empty()) return;
    const std::filesystem::path dir = acceptance->empty()
                                          ? std::filesystem::path(*run) / "acceptance"
                                          : std::filesystem::path(*acceptance);
    const std::vector<std::filesystem::path> files = calib::FindAcceptanceFiles(dir);
    if (files.empty())
      throw std::runtime_error(dir.string() + ": no <serial>/acceptance.json to certify");
    for (const std::filesystem::path& file : files) {
      const std::string serial = file.parent_path().filename().string();
      const std::filesystem::path constants =
          fit->empty() ? std::filesystem::path() : calib::FindConstantsOf(*fit, serial);
      const calib::WrittenCertificate c = calib::WriteCertificate(
          calib::ReadCertificateInputs(file, constants, *operator_name, ADAHRS_VERSION),
          *certificates);
      std::cout << "wrote " << c.html.string()
                << (c.pdf ? " and " + c.pdf->string() : " (" + c.pdf_error + ")") << "\n";
    }
  });
}

}  // namespace adahrs::apps
