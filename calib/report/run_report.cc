#include "calib/report/run_report.h"

#include <map>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/constants/constants_file.h"
#include "calib/constants/recording_checksum.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/report/acceptance_section.h"
#include "calib/report/ads_report_sections.h"
#include "calib/report/html_builder.h"
#include "calib/report/imu_report_sections.h"
#include "calib/report/json_tables.h"
#include "calib/report/svg_plot.h"
#include "calib/report/time_series.h"
#include "calib/report/verdict_section.h"
#include "calib/sequence/sequence_json.h"
#include "common/atomic_file.h"
#include "common/html_page.h"
#include "common/param_reader.h"
#include "common/unit_kind.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

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

std::string Summary(const std::filesystem::path& run_dir, const hil::RecordingMeta& meta) {
  const auto text = [](const std::optional<std::string>& value) {
    return value.value_or("(not recorded)");
  };
  HtmlTable run{"run", {"item", "value"}, {}};
  run.rows.push_back({"run directory", run_dir.string()});
  run.rows.push_back({"run id", text(meta.run_id)});
  run.rows.push_back({"started (UTC)", text(meta.started_utc)});
  run.rows.push_back({"status", text(meta.status)});
  run.rows.push_back({"sequence file", text(meta.sequence_file)});
  // The sequence and station documents are kept as written; only their names are shown here.
  for (const auto& [label, document] :
       {std::pair{"sequence", &meta.sequence}, std::pair{"station", &meta.station}}) {
    if (*document && (*document)->contains("name")) {
      run.rows.push_back({label, (*document)->at("name").get<std::string>()});
    }
  }
  run.rows.push_back({"time base", text(meta.time_base)});
  if (meta.local_gravity_mps2) {
    run.rows.push_back({"local gravity (m/s^2)", FormatNumber(*meta.local_gravity_mps2, 8)});
  }
  std::string html = RenderTable(run);
  HtmlTable units{
      "units", {"role", "kind", "serial", "firmware", "slot", "constants version", "mode"}, {}};
  for (const hil::RecordingUnit& u : meta.units) {
    units.rows.push_back({u.role,
                          u.kind ? common::UnitKindName(*u.kind) : "",
                          u.serial,
                          u.firmware.value_or(""),
                          std::to_string(u.slot.value_or(0)),
                          std::to_string(u.constants_version.value_or(0)),
                          std::to_string(u.mode.value_or(0))});
  }
  html += RenderTable(units);
  if (meta.rejected_intervals.empty()) {
    html += "<p>No rejected intervals.</p>\n";
  } else {
    html += RenderJsonTables("rejected intervals (rows inside are not calibration data)",
                             hil::RejectedIntervalsJson(meta.rejected_intervals));
  }
  return html;
}

// The acceptance files of the run: those of `acceptance_dir`, else of <run>/acceptance.
std::vector<AcceptanceFile> AcceptanceFilesOfRun(
    const std::filesystem::path& run_dir,
    const std::optional<std::filesystem::path>& acceptance_dir) {
  if (acceptance_dir && !std::filesystem::is_directory(*acceptance_dir)) {
    throw std::runtime_error(acceptance_dir->string() + ": acceptance directory does not exist");
  }
  std::vector<AcceptanceFile> files;
  for (const std::filesystem::path& file :
       FindAcceptanceFiles(acceptance_dir.value_or(run_dir / "acceptance"))) {
    files.push_back(ReadAcceptanceFile(file));
  }
  return files;
}

// The acceptance section: per-unit acceptance files first, a fit directory's acceptance.json next.
std::string Acceptance(const std::filesystem::path& run_dir,
                       const std::optional<std::filesystem::path>& acceptance_dir,
                       const std::vector<AcceptanceFile>& files,
                       const FitInputs& fit) {
  if (!files.empty()) return AcceptanceSectionBody(files);
  if (fit.acceptance) return RenderJsonTables("acceptance", *fit.acceptance);
  const std::filesystem::path dir = acceptance_dir.value_or(run_dir / "acceptance");
  return NotAvailable(
      "acceptance.json",
      "no <serial>/acceptance.json in " + dir.string() + "; fit directory: " + fit.why_missing);
}

const ConstantsFile* ConstantsOf(const FitInputs& fit, const std::string& serial) {
  const auto found = fit.constants.find(serial);
  return found == fit.constants.end() ? nullptr : &found->second;
}

// What one streamed pass over the recording gives the report (every row is still read and
// checked; only per-acquisition sums and decimated series are kept): the ADS sections of every
// ADS unit by serial, the time series of the run, and the IMU calibration data of the units
// recorded in raw mode (as LoadImuRuns collects it, from the same pass), or why there is none.
struct StreamedSections {
  std::map<std::string, std::string> ads_html;
  std::string time_series_html;
  std::optional<ImuRunData> imu;
  std::string imu_why;
};

// The collector of the run's IMU calibration data, or nullptr (no IMU recorded in raw mode, or
// the run cannot give calibration data: `why` says so).
std::unique_ptr<ImuRunCollector> ImuCollector(const std::filesystem::path& run_dir,
                                              const hil::RecordingMeta& meta,
                                              ImuRunData* data,
                                              std::string* why) {
  std::vector<std::string> serials;
  for (const hil::RecordingUnit& u : meta.units) {
    if (u.kind == common::UnitKind::kImu && u.mode.value_or(0) == 0 && !u.serial.empty()) {
      serials.push_back(u.serial);
    }
  }
  if (serials.empty()) return nullptr;
  const std::string run = run_dir.string();
  try {
    if (!meta.local_gravity_mps2) {
      throw ImuInputError(
          run +
          ": meta.json: $.local_gravity_mps2 missing (the station's local gravity is needed)");
    }
    if (!meta.sequence) throw ImuInputError(run + ": meta.json: $.sequence missing");
    return std::make_unique<ImuRunCollector>(
        run,
        RecordingSha256(run_dir),
        SequenceFromJson(*meta.sequence, run + "/meta.json $.sequence"),
        *meta.local_gravity_mps2,
        serials,
        meta.rejected_intervals,
        data);
  } catch (const std::exception& e) {
    *why = e.what();
    return nullptr;
  }
}

StreamedSections StreamSections(const std::filesystem::path& run_dir,
                                const hil::RecordingMeta& meta,
                                const FitInputs& fit,
                                const Specification& spec) {
  StreamedSections streamed;
  std::vector<AdsReportAccumulator> units;
  for (const hil::RecordingUnit& u : meta.units) {
    if (u.kind == common::UnitKind::kImu) continue;
    units.emplace_back(u.serial, meta, ConstantsOf(fit, u.serial), run_dir.string(), spec);
  }
  ImuRunData imu;
  std::unique_ptr<ImuRunCollector> collector = ImuCollector(run_dir, meta, &imu, &streamed.imu_why);
  TimeSeriesAccumulator time_series;
  hil::RowSinks sinks;
  sinks.ads = [&](hil::AdsRecordRow&& row, int line) {
    for (AdsReportAccumulator& unit : units) unit.Add(row, line);
    time_series.Add(row);
  };
  sinks.imu = [&](hil::ImuRecordRow&& row, int line) {
    time_series.Add(row);
    if (collector == nullptr) return;
    try {
      collector->Take(row, line);
    } catch (const std::exception& e) {  // the figures of time go on without calibration data
      streamed.imu_why = e.what();
      collector.reset();
    }
  };
  hil::StreamRecording(run_dir, sinks);
  if (collector != nullptr) {
    try {
      collector->Finish();
      streamed.imu = std::move(imu);
    } catch (const std::exception& e) {
      streamed.imu_why = e.what();
    }
  }
  for (const AdsReportAccumulator& unit : units) streamed.ads_html[unit.serial()] = unit.Sections();
  streamed.time_series_html = time_series.Figures();
  return streamed;
}

}  // namespace

std::string BuildRunReport(const std::filesystem::path& run_dir,
                           const std::optional<std::filesystem::path>& fit_dir,
                           const std::optional<std::filesystem::path>& acceptance_dir,
                           const std::optional<Specification>& specification) {
  const hil::RecordingMeta meta = hil::ReadRecordingMeta(run_dir).meta;
  const FitInputs fit = LoadFit(fit_dir);
  const StreamedSections streamed =
      StreamSections(run_dir, meta, fit, specification.value_or(Specification::Reference()));
  const std::map<std::string, std::string>& ads_html = streamed.ads_html;
  const double g_local_mps2 = meta.local_gravity_mps2.value_or(0.0);
  const std::optional<ImuRunData>& imu = streamed.imu;
  const std::string& imu_why = streamed.imu_why;

  const std::string title =
      fmt::format("Calibration report: run {}", meta.run_id.value_or(run_dir.filename().string()));
  const std::vector<AcceptanceFile> acceptance = AcceptanceFilesOfRun(run_dir, acceptance_dir);
  std::string body = Section(
      "verdict",
      2,
      "Verdict",
      VerdictSectionBody(acceptance, meta.sequence ? meta.sequence->value("name", "") : ""));
  body += Section("summary", 2, "Run", Summary(run_dir, meta));
  body += Section("time-series",
                  2,
                  "Time series",
                  streamed.time_series_html.empty()
                      ? NotAvailable("time series", "the recording has no rows")
                      : streamed.time_series_html);
  std::string units;
  for (const hil::RecordingUnit& u : meta.units) {
    const std::string& serial = u.serial;
    const ConstantsFile* constants = ConstantsOf(fit, serial);
    std::string unit_html;
    if (u.kind == common::UnitKind::kImu) {
      if (u.mode.value_or(0) != 0) {
        // Calibration figures are of raw rows; a unit recorded in a compensated mode (an
        // acceptance run) has none, and its judgement is page one's.
        unit_html = fmt::format(
            "<p class=\"note\">Recorded in mode {} (compensated): the calibration figures need "
            "raw rows (mode 0). This unit's outputs are judged in the Verdict and Acceptance "
            "sections.</p>\n",
            *u.mode);
      } else if (imu && imu->units.count(serial)) {
        unit_html = ImuReportSections(imu->units.at(serial), constants, g_local_mps2);
      } else {
        unit_html = NotAvailable("IMU calibration data",
                                 imu ? "no calibration rows for " + serial : imu_why);
      }
    } else {
      unit_html = ads_html.at(serial);
    }
    units += Section(serial, 2, fmt::format("Unit {} ({})", serial, u.role), unit_html);
  }
  body += units;
  body +=
      Section("acceptance", 2, "Acceptance", Acceptance(run_dir, acceptance_dir, acceptance, fit));
  body += Section("evaluation",
                  2,
                  "Evaluation against simulator truth",
                  fit.evaluation ? RenderJsonTables("evaluation", *fit.evaluation)
                                 : NotAvailable("evaluation.json", fit.why_missing));
  return common::HtmlPage(
      title,
      fmt::format(
          "<h1>{}</h1>\n"
          "<p>Units: accelerations in g or mg (1 mg = 9.80665e-3 m/s^2) or m/s^2, rates in deg/s, "
          "altitude in ft, airspeed in kt, temperatures in degC as the chamber controller reports "
          "them; raw channels in duty (T1/T2 - 0.5) and converter counts. Standard errors are 1 "
          "sigma.</p>\n{}",
          XmlEscape(title),
          body));
}

void WriteRunReport(const std::filesystem::path& run_dir,
                    const std::optional<std::filesystem::path>& fit_dir,
                    const std::filesystem::path& out,
                    const std::optional<std::filesystem::path>& acceptance_dir,
                    const std::optional<Specification>& specification) {
  common::WriteFileAtomically(out, BuildRunReport(run_dir, fit_dir, acceptance_dir, specification));
}

}  // namespace adahrs::calib
