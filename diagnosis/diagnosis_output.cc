#include "diagnosis/diagnosis_output.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/constants/recording_checksum.h"
#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"
#include "common/atomic_file.h"
#include "common/html_page.h"
#include "common/unit_kind.h"
#include "diagnosis/ads_diagnosis.h"
#include "diagnosis/channel_diagnosis.h"

namespace adahrs::diagnosis {
namespace {

using nlohmann::json;

constexpr const char* kModel =
    "pipeline forward model (nominal), fitted to this recording: IMU thermal polynomials, scale "
    "and cross-axis, "
    "gyro span nonlinearity; ADS bivariate polynomial of each bridge's code in pressure and bridge "
    "voltage";

constexpr const char* kChannelModel =
    "generic thermal model, fitted to this recording: bias polynomial in temperature, scale and "
    "its tempco per "
    "reference input";

// The unit kinds a run's meta.json lists ("imu", "ads"), read by the recording reader (which
// refuses a missing file or an unknown format version, naming the file).
std::set<std::string> UnitKinds(const std::filesystem::path& run) {
  std::set<std::string> kinds;
  for (const hil::RecordingUnit& u : hil::ReadRecordingMeta(run).meta.units) {
    if (u.kind) kinds.insert(common::UnitKindName(*u.kind));
  }
  return kinds;
}

// Every ADS unit of `run` (or only `serial`), diagnosed from its calibration points, selected in
// one streamed pass over ads.csv; units in the order of their first row.
void DiagnoseAdsRun(const std::filesystem::path& run,
                    const std::optional<std::string>& serial,
                    const DiagnosisOptions& options,
                    DiagnosisRun* out,
                    std::vector<std::string>* seen) {
  const hil::RecordingMeta meta = hil::ReadRecordingMeta(run).meta;
  std::vector<std::string> serials;
  std::vector<calib::AdsPointSelector> selectors;  // one per serial diagnosed, in `serials` order
  hil::RowSinks sinks;
  sinks.ads = [&](hil::AdsRecordRow&& r, int line) {
    if (std::find(serials.begin(), serials.end(), r.unit) == serials.end()) {
      serials.push_back(r.unit);
      if (!serial || r.unit == *serial) selectors.emplace_back(meta, r.unit, run.string());
    }
    for (calib::AdsPointSelector& s : selectors) s.Add(r, line);
  };
  const hil::Recording rec = hil::StreamRecording(run, sinks);
  out->notes.insert(out->notes.end(), rec.notes.begin(), rec.notes.end());
  out->recordings.push_back({run.string(), calib::RecordingSha256(run)});
  size_t next = 0;
  for (const std::string& s : serials) {
    seen->push_back(s);
    if (serial && s != *serial) continue;
    out->units.push_back(DiagnoseAds(s, selectors[next++].Points(), options));
    out->units.back().notes.push_back("points of " + run.string());
  }
}

std::string Figures(const UnitDiagnosis& u) {
  std::string body;
  for (const ChannelFitSummary& c : u.channels) {
    bool found = false;
    for (const Finding& f : u.findings) found = found || f.channel == c.channel;
    for (const Unexplained& x : u.unexplained) found = found || x.channel == c.channel;
    if (!found || c.plot_t_s.empty()) continue;
    calib::Plot p;
    const bool points = c.residuals == ChannelFitSummary::Residuals::kPerCalibrationPoint;
    p.title = fmt::format("{} {}: residual of each {}",
                          u.serial,
                          c.channel,
                          points ? "calibration point" : "1 s cell");
    p.x_label = points ? "chamber temperature (degC)" : "thermometer temperature (degC)";
    p.y_label = "residual (" + c.unit + ")";
    p.series.push_back({"baseline model",
                        c.plot_temp_c,
                        c.plot_residual_baseline,
                        calib::PlotSeries::Style::kPoints});
    p.series.push_back({"with the findings",
                        c.plot_temp_c,
                        c.plot_residual_final,
                        calib::PlotSeries::Style::kPoints});
    body += calib::RenderSvg(p);
  }
  return body;
}

std::string UnitSection(const UnitDiagnosis& u) {
  std::string body = "<p>" +
                     calib::XmlEscape(fmt::format(
                         "{} rows in {} segments ({} cells of 1 s), thermometers span {:.1f} degC.",
                         u.rows,
                         u.segments,
                         u.cells,
                         u.temp_span_c)) +
                     "</p>";
  if (u.NoMissingPhysics()) {
    body +=
        "<p>No missing physics found: every candidate this recording can test stays below its "
        "detection limit; those it cannot test are said so (table below).</p>";
  } else if (u.findings.empty()) {
    body += "<p>" + calib::XmlEscape(u.Verdict()) + ": see the unexplained structure below.</p>";
  } else {
    body += "<ul>";
    for (const Finding& f : u.findings) body += "<li>" + calib::XmlEscape(f.words) + "</li>";
    body += "</ul>";
    calib::HtmlTable t{
        "Findings: held-out RMS of the cell means without and with each term, channel unit",
        {"effect",
         "channel",
         "magnitude",
         "held-out RMS before",
         "after",
         "unit",
         "evidence (largest contribution)"},
        {}};
    for (const Finding& f : u.findings) {
      std::string mag;
      for (const FindingComponent& c : f.components) {
        mag += fmt::format("{}{} {} ± {} {}",
                           mag.empty() ? "" : "; ",
                           c.name,
                           calib::FormatNumber(c.magnitude, 3),
                           calib::FormatNumber(c.standard_error, 2),
                           c.unit);
      }
      std::string ev;
      for (const std::string& e : f.evidence) ev += (ev.empty() ? "" : "; ") + e;
      t.rows.push_back({f.effect,
                        f.channel,
                        mag,
                        calib::FormatNumber(f.held_out_rms_before, 3),
                        calib::FormatNumber(f.held_out_rms_after, 3),
                        f.rms_unit,
                        ev});
    }
    body += calib::RenderTable(t);
  }
  if (!u.unexplained.empty()) {
    calib::HtmlTable t{
        "Unexplained structure (located, not fitted)", {"channel", "where", "description"}, {}};
    for (const Unexplained& x : u.unexplained)
      t.rows.push_back({x.channel, x.where, x.description});
    body += calib::RenderTable(t);
  }
  calib::HtmlTable ch{"Per channel: held-out RMS of the 1 s cell means (leave one segment out)",
                      {"channel", "baseline", "final", "white noise alone", "unit"},
                      {}};
  for (const ChannelFitSummary& c : u.channels) {
    ch.rows.push_back({c.channel,
                       calib::FormatNumber(c.held_out_rms_baseline, 3),
                       calib::FormatNumber(c.held_out_rms_final, 3),
                       calib::FormatNumber(c.white_noise_rms, 3),
                       c.unit});
  }
  body += calib::RenderTable(ch);
  body += Figures(u);
  calib::HtmlTable lim{
      "Detection limits: the smallest magnitude this recording would have found (80 % power)",
      {"effect", "channel", "smallest detectable"},
      {}};
  for (const DetectionLimit& d : u.detection_limits) {
    std::string v;
    for (const FindingComponent& c : d.limits) {
      v += fmt::format(
          "{}{} {} {}", v.empty() ? "" : "; ", c.name, calib::FormatNumber(c.magnitude, 2), c.unit);
    }
    const bool said = d.note.rfind("not testable here", 0) == 0;
    lim.rows.push_back(
        {d.effect, d.channel, d.limits.empty() ? (said ? "" : "not testable here: ") + d.note : v});
  }
  body += calib::RenderTable(lim);
  for (const std::string& n : u.notes) body += "<p class=\"note\">" + calib::XmlEscape(n) + "</p>";
  return calib::Section("unit-" + u.serial, 2, u.serial, body);
}

}  // namespace

json DiagnosisRun::ToJson() const {
  json recs = json::array(), units_json = json::array(), findings = json::array(),
       unexplained = json::array(), limits = json::array();
  for (const calib::RecordingReference& r : recordings)
    recs.push_back({{"path", r.path}, {"sha256", r.sha256}});
  for (const UnitDiagnosis& u : units) {
    units_json.push_back(u.ToJson());
    for (const Finding& f : u.findings) {
      json j = f.ToJson();
      j["unit_serial"] = u.serial;
      findings.push_back(j);
    }
    for (const Unexplained& x : u.unexplained) {
      json j = x.ToJson();
      j["unit_serial"] = u.serial;
      unexplained.push_back(j);
    }
    for (const DetectionLimit& d : u.detection_limits) {
      json j = d.ToJson();
      j["unit_serial"] = u.serial;
      limits.push_back(j);
    }
  }
  return {{"format", "adahrs-diagnosis"},
          {"format_version", kDiagnosisFormatVersion},
          {"recording", recs},
          {"model", model},
          {"findings", findings},
          {"unexplained", unexplained},
          {"detection_limits", limits},
          {"units", units_json},
          {"notes", notes}};
}

DiagnosisRun DiagnoseRuns(const std::vector<std::filesystem::path>& runs,
                          const std::optional<std::string>& serial,
                          const DiagnosisOptions& options) {
  std::vector<std::filesystem::path> imu_runs, ads_runs;
  for (const std::filesystem::path& run : runs) {
    const std::set<std::string> kinds = UnitKinds(run);
    if (kinds.count("ads")) ads_runs.push_back(run);
    if (kinds.count("imu") || !kinds.count("ads")) imu_runs.push_back(run);
  }
  DiagnosisRun out;
  out.model = kModel;
  std::vector<std::string> seen;
  if (!imu_runs.empty()) {
    const calib::ImuRunData data = calib::LoadImuRuns(imu_runs);
    out.recordings = data.recordings;
    out.notes = data.notes;
    for (const auto& [s, unit] : data.units) {
      seen.push_back(s);
      if (serial && s != *serial) continue;
      out.units.push_back(DiagnoseImu(BuildDiagnosisData(unit, data.local_gravity_mps2), options));
    }
  }
  for (const std::filesystem::path& run : ads_runs)
    DiagnoseAdsRun(run, serial, options, &out, &seen);
  if (serial && std::find(seen.begin(), seen.end(), *serial) == seen.end()) {
    std::string have;
    for (const std::string& s : seen) have += (have.empty() ? "" : ", ") + s;
    throw calib::ImuInputError("unit " + *serial + " is not in the recordings (they hold: " + have +
                               ")");
  }
  if (out.units.empty())
    throw calib::ImuInputError("the recordings hold no IMU or ADS calibration data");
  return out;
}

DiagnosisRun DiagnoseChannelFiles(const std::vector<std::filesystem::path>& sidecars,
                                  const DiagnosisOptions& options) {
  DiagnosisRun out;
  out.model = kChannelModel;
  for (const std::filesystem::path& sidecar : sidecars) {
    const ChannelRecording rec = ReadChannelRecording(sidecar);
    out.recordings.push_back({rec.csv, rec.sha256});
    out.units.push_back(DiagnoseChannels(rec, options));
    // The reader's notes are about the recording as read: the run's notes, printed, not the unit's.
    std::vector<std::string>& unit_notes = out.units.back().notes;
    unit_notes.erase(
        unit_notes.begin(),
        unit_notes.begin() + static_cast<long>(std::min(unit_notes.size(), rec.notes.size())));
    out.notes.insert(out.notes.end(), rec.notes.begin(), rec.notes.end());
  }
  return out;
}

std::string DiagnosisHtml(const DiagnosisRun& run) {
  std::string body =
      "<h1>Diagnosis</h1><p>" + calib::XmlEscape("Compared with: " + run.model) + "</p><ul>";
  for (const calib::RecordingReference& r : run.recordings)
    body += "<li>" + calib::XmlEscape(r.path + " (sha256 " + r.sha256 + ")") + "</li>";
  body += "</ul>";
  for (const std::string& n : run.notes)
    body += "<p class=\"note\">" + calib::XmlEscape(n) + "</p>";
  for (const UnitDiagnosis& u : run.units) body += UnitSection(u);
  return common::HtmlPage("adahrs diagnosis", body);
}

void WriteDiagnosis(const DiagnosisRun& run, const std::filesystem::path& out_dir) {
  std::filesystem::create_directories(out_dir);
  common::WriteFileAtomically(out_dir / "diagnosis.json", run.ToJson().dump(2) + "\n");
  common::WriteFileAtomically(out_dir / "report.html", DiagnosisHtml(run));
}

}  // namespace adahrs::diagnosis
