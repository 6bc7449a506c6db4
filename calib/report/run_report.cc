#include "calib/report/run_report.h"

#include <fstream>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/report/acceptance_section.h"
#include "calib/report/ads_report_sections.h"
#include "calib/report/html_builder.h"
#include "calib/report/imu_report_sections.h"
#include "calib/report/json_tables.h"
#include "calib/report/svg_plot.h"
#include "common/param_reader.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:70em;margin:1em auto}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 6px;"
    "font-size:90%}caption{text-align:left;font-weight:bold}.pass{background:#d8f0d8}"
    ".fail{background:#f6d0d0}.unavailable{color:#a33;font-style:italic}";

struct FitInputs {
  std::map<std::string, ConstantsFile> constants;  // by serial
  std::optional<nlohmann::json> acceptance;
  std::optional<nlohmann::json> evaluation;
  std::string why_missing;  // when there is no fit directory
};

FitInputs LoadFit(const std::optional<std::filesystem::path>& fit_dir) {
  FitInputs fit;
  if (!fit_dir) {
    fit.why_missing = "no fit directory given (--fit)";
    return fit;
  }
  if (!std::filesystem::is_directory(*fit_dir)) {
    throw std::runtime_error(fit_dir->string() + ": fit directory does not exist");
  }
  fit.why_missing = "not in " + fit_dir->string();
  for (const auto& entry : std::filesystem::directory_iterator(*fit_dir)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().filename().string();
    if (name == "acceptance.json") {
      fit.acceptance = common::ParamReader::LoadFile(entry.path().string());
    } else if (name == "evaluation.json") {
      fit.evaluation = common::ParamReader::LoadFile(entry.path().string());
    } else {
      const nlohmann::json document = common::ParamReader::LoadFile(entry.path().string());
      if (document.is_object() && document.value("format", "") == kConstantsFormatName) {
        ConstantsFile file = ReadConstantsFile(entry.path());
        fit.constants[file.serial] = std::move(file);
      }
    }
  }
  return fit;
}

std::string Summary(const std::filesystem::path& run_dir, const nlohmann::json& meta) {
  const auto text = [&](const char* key) {
    return meta.contains(key) && meta[key].is_string() ? meta[key].get<std::string>()
                                                       : std::string("(not recorded)");
  };
  HtmlTable run{"run", {"item", "value"}, {}};
  run.rows.push_back({"run directory", run_dir.string()});
  run.rows.push_back({"run id", text("run_id")});
  run.rows.push_back({"started (UTC)", text("started_utc")});
  run.rows.push_back({"status", text("status")});
  run.rows.push_back({"sequence file", text("sequence_file")});
  if (meta.contains("sequence") && meta["sequence"].contains("name")) {
    run.rows.push_back({"sequence", meta["sequence"]["name"].get<std::string>()});
  }
  if (meta.contains("station") && meta["station"].contains("name")) {
    run.rows.push_back({"station", meta["station"]["name"].get<std::string>()});
  }
  run.rows.push_back({"time base", text("time_base")});
  if (meta.contains("local_gravity_mps2")) {
    run.rows.push_back(
        {"local gravity (m/s^2)", FormatNumber(meta["local_gravity_mps2"].get<double>(), 8)});
  }
  std::string html = RenderTable(run);
  HtmlTable units{
      "units", {"role", "kind", "serial", "firmware", "slot", "constants version", "mode"}, {}};
  for (const auto& u : meta.value("units", nlohmann::json::array())) {
    units.rows.push_back({u.value("role", ""),
                          u.value("kind", ""),
                          u.value("serial", ""),
                          u.value("firmware", ""),
                          std::to_string(u.value("slot", 0)),
                          std::to_string(u.value("constants_version", 0)),
                          std::to_string(u.value("mode", 0))});
  }
  html += RenderTable(units);
  const auto rejected = meta.value("rejected_intervals", nlohmann::json::array());
  if (rejected.empty()) {
    html += "<p>No rejected intervals.</p>\n";
  } else {
    html += RenderJsonTables("rejected intervals (rows inside are not calibration data)", rejected);
  }
  return html;
}

// The acceptance section: per-unit acceptance files first, a fit directory's acceptance.json next.
std::string Acceptance(const std::filesystem::path& run_dir,
                       const std::optional<std::filesystem::path>& acceptance_dir,
                       const FitInputs& fit) {
  if (acceptance_dir && !std::filesystem::is_directory(*acceptance_dir)) {
    throw std::runtime_error(acceptance_dir->string() + ": acceptance directory does not exist");
  }
  const std::filesystem::path dir = acceptance_dir.value_or(run_dir / "acceptance");
  std::vector<nlohmann::json> documents;
  for (const std::filesystem::path& file : FindAcceptanceFiles(dir)) {
    documents.push_back(ReadAcceptanceFile(file));
  }
  if (!documents.empty()) return AcceptanceSectionBody(documents);
  if (fit.acceptance) return RenderJsonTables("acceptance", *fit.acceptance);
  return NotAvailable(
      "acceptance.json",
      "no <serial>/acceptance.json in " + dir.string() + "; fit directory: " + fit.why_missing);
}

const ConstantsFile* ConstantsOf(const FitInputs& fit, const std::string& serial) {
  const auto found = fit.constants.find(serial);
  return found == fit.constants.end() ? nullptr : &found->second;
}

// The ADS sections of every ADS unit of the run, by serial, from one streamed pass over the
// recording (every row is still read and checked; only per-acquisition sums are kept).
std::map<std::string, std::string> AdsSectionsBySerial(const std::filesystem::path& run_dir,
                                                       const nlohmann::json& meta,
                                                       const FitInputs& fit) {
  std::vector<AdsReportAccumulator> units;
  for (const auto& u : meta.value("units", nlohmann::json::array())) {
    if (u.value("kind", "") == "imu") continue;
    const std::string serial = u.value("serial", "");
    units.emplace_back(serial, meta, ConstantsOf(fit, serial));
  }
  hil::RowSinks sinks;
  sinks.ads = [&](hil::AdsRecordRow&& row, int) {
    for (AdsReportAccumulator& unit : units) unit.Add(row);
  };
  hil::StreamRecording(run_dir, sinks);
  std::map<std::string, std::string> html;
  for (const AdsReportAccumulator& unit : units) html[unit.serial()] = unit.Sections();
  return html;
}

}  // namespace

std::string BuildRunReport(const std::filesystem::path& run_dir,
                           const std::optional<std::filesystem::path>& fit_dir,
                           const std::optional<std::filesystem::path>& acceptance_dir) {
  const nlohmann::json meta = hil::ReadRecordingMeta(run_dir).meta;
  const FitInputs fit = LoadFit(fit_dir);
  const std::map<std::string, std::string> ads_html = AdsSectionsBySerial(run_dir, meta, fit);
  const double g_local_mps2 = meta.value("local_gravity_mps2", 0.0);

  std::optional<ImuRunData> imu;
  std::string imu_why;
  bool has_imu = false;
  for (const auto& u : meta.value("units", nlohmann::json::array()))
    has_imu |= u.value("kind", "") == "imu";
  if (has_imu) {
    try {
      imu = LoadImuRuns({run_dir});
    } catch (const std::exception& e) {
      imu_why = e.what();
    }
  }

  const std::string title =
      fmt::format("Calibration report: run {}", meta.value("run_id", run_dir.filename().string()));
  std::string body = Section("summary", 2, "Run", Summary(run_dir, meta));
  std::string units;
  for (const auto& u : meta.value("units", nlohmann::json::array())) {
    const std::string serial = u.value("serial", "");
    const ConstantsFile* constants = ConstantsOf(fit, serial);
    std::string unit_html;
    if (u.value("kind", "") == "imu") {
      if (imu && imu->units.count(serial)) {
        unit_html = ImuReportSections(imu->units.at(serial), constants, g_local_mps2);
      } else {
        unit_html = NotAvailable("IMU calibration data",
                                 imu ? "no calibration rows for " + serial : imu_why);
      }
    } else {
      unit_html = ads_html.at(serial);
    }
    units +=
        Section(serial, 2, fmt::format("Unit {} ({})", serial, u.value("role", "")), unit_html);
  }
  body += units;
  body += Section("acceptance", 2, "Acceptance", Acceptance(run_dir, acceptance_dir, fit));
  body += Section("evaluation",
                  2,
                  "Evaluation against simulator truth",
                  fit.evaluation ? RenderJsonTables("evaluation", *fit.evaluation)
                                 : NotAvailable("evaluation.json", fit.why_missing));
  return fmt::format(
      "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
      "<meta "
      "charset=\"utf-8\"/>\n<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n<h1>{}</h1>\n"
      "<p>Units: accelerations in g or mg (1 mg = 9.80665e-3 m/s^2) or m/s^2, rates in deg/s, "
      "altitude in ft, airspeed in kt, temperatures in degC as the chamber controller reports "
      "them; raw channels in duty (T1/T2 - 0.5) and converter counts. Standard errors are 1 "
      "sigma.</p>\n{}</body>\n</html>\n",
      XmlEscape(title),
      kStyle,
      XmlEscape(title),
      body);
}

void WriteRunReport(const std::filesystem::path& run_dir,
                    const std::optional<std::filesystem::path>& fit_dir,
                    const std::filesystem::path& out,
                    const std::optional<std::filesystem::path>& acceptance_dir) {
  const std::string html = BuildRunReport(run_dir, fit_dir, acceptance_dir);
  const std::filesystem::path temporary = out.string() + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary);
    if (!file || !(file << html) || !file.flush()) {
      throw std::runtime_error(temporary.string() + ": cannot write the report");
    }
  }
  std::filesystem::rename(temporary, out);
}

}  // namespace adahrs::calib
