#include "diagnosis/replay_check_report.h"

#include <fmt/format.h>

#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"
#include "common/atomic_file.h"
#include "common/html_page.h"
#include "diagnosis/diagnosis_output.h"

namespace adahrs::diagnosis {
namespace {

std::string ChannelFigure(const std::string& serial, const ChannelReplayFit& c) {
  calib::Plot p;
  p.title = fmt::format(
      "{} {}: mean residual of each acquisition, recorded - replayed", serial, c.channel);
  p.x_label = "acquisition (in run order)";
  p.y_label = "residual (" + c.unit + ")";
  calib::PlotSeries base{"base model", {}, {}, calib::PlotSeries::Style::kPoints};
  calib::PlotSeries model{"model.json", {}, {}, calib::PlotSeries::Style::kPoints};
  calib::PlotBand noise{"noise alone (2 standard errors)", {}, {}, {}};
  for (size_t i = 0; i < c.acquisitions.size(); ++i) {
    const AcquisitionResidual& a = c.acquisitions[i];
    const double x = static_cast<double>(i + 1);
    base.x.push_back(x);
    base.y.push_back(a.base);
    model.x.push_back(x);
    model.y.push_back(a.model);
    noise.x.push_back(x);
    noise.y_lo.push_back(-2.0 * a.noise_se);
    noise.y_hi.push_back(2.0 * a.noise_se);
  }
  p.series = {base, model};
  p.bands = {noise};
  return calib::RenderSvg(p);
}

std::string CheckSection(const ReplayComparison& c, size_t index) {
  std::string body = "<p>" +
                     calib::XmlEscape(fmt::format(
                         "{} re-simulated with the base model ({}) and with model.json ({}); {}.",
                         c.recording.string(),
                         c.base_replay.string(),
                         c.model_replay.string(),
                         c.held_out ? "held out: the diagnosis did not see this run"
                                    : "a diagnosed run: not held out")) +
                     "</p>";
  for (const UnitReplayFit& u : c.units) {
    calib::HtmlTable t{
        u.serial + ": RMS over the acquisitions of the mean residual, recorded - replayed",
        {"channel", "base model", "model.json", "noise alone", "unit", "acquisitions"},
        {}};
    std::string figures;
    for (const ChannelReplayFit& ch : u.channels) {
      t.rows.push_back({ch.channel,
                        calib::FormatNumber(ch.rms_base, 3),
                        calib::FormatNumber(ch.rms_model, 3),
                        calib::FormatNumber(ch.rms_noise, 2),
                        ch.unit,
                        std::to_string(ch.acquisitions.size())});
      if (std::max(ch.rms_base, ch.rms_model) > 2.0 * ch.rms_noise)
        figures += ChannelFigure(u.serial, ch);
    }
    body += calib::RenderTable(t) + figures;
  }
  return calib::Section(fmt::format("check-{}", index), 2, c.recording.filename().string(), body);
}

}  // namespace

std::string ReplayCheckHtml(const std::vector<ReplayComparison>& checks) {
  std::string body =
      "<h1>Re-simulation check</h1><p>Each run's stimulus replayed with the unit model the "
      "diagnosis "
      "started from and with the model it wrote (docs/diagnose.md).</p>";
  if (checks.empty()) body += calib::NotAvailable("a check", "no run held a diagnosed unit");
  for (size_t i = 0; i < checks.size(); ++i) body += CheckSection(checks[i], i);
  return common::HtmlPage("adahrs re-simulation check", body);
}

void WriteReplayCheck(const std::vector<ReplayComparison>& checks,
                      const std::filesystem::path& out_dir) {
  nlohmann::json all = nlohmann::json::array();
  for (const ReplayComparison& c : checks) all.push_back(c.ToJson());
  std::filesystem::create_directories(out_dir);
  common::WriteFileAtomically(out_dir / "replay_check.json", all.dump(2) + "\n");
  common::WriteFileAtomically(out_dir / "replay_check.html", ReplayCheckHtml(checks));
}

}  // namespace adahrs::diagnosis
