#include "calib/report/imu_noise_section.h"

#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"
#include "calib/solvers/allan_terms.h"
#include "common/units.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

constexpr double kMpsPerMg = common::kMpsPerMilliG;
constexpr double kMpsPerUg = common::kMpsPerMicroG;
constexpr double kSqrtSecondsPerHour = 60.0;  // x unit/sqrt(s) -> unit/sqrt(h)
constexpr double kSecondsPerHour = 3600.0;
constexpr double kAtRestDps = 0.5;  // a gyro acquisition at the table's 0 deg/s
constexpr size_t kMinRestSamples = 20;
constexpr const char* kAxes[3] = {"x", "y", "z"};

// The longest acquisition of the unit at rest, or nullptr.
const ImuAcquisition* LongestAtRest(const ImuUnitData& d) {
  const ImuAcquisition* best = nullptr;
  auto consider = [&](const std::vector<ImuAcquisition>& acquisitions) {
    for (const ImuAcquisition& a : acquisitions) {
      if (std::abs(a.rate_dps) > kAtRestDps) continue;
      if (best == nullptr || a.samples.size() > best->samples.size()) best = &a;
    }
  };
  consider(d.accel);
  consider(d.gyro);
  consider(d.cross_axis);
  return best;
}

std::string TauNote(const AllanTerms& t) {
  return FormatNumber(t.white_tau_s, 3) +
         (t.white_tau_s < 1.0 ? " (record too short for 1 s)" : "");
}

std::string FloorText(double value, const AllanTerms& t) {
  return (t.minimum_at_longest_tau ? "<= " : "") + FormatNumber(value, 3) + " at tau " +
         FormatNumber(t.bias_instability_tau_s, 3) + " s" +
         (t.minimum_at_longest_tau ? " (no floor within the record)" : "");
}

}  // namespace

std::string ImuNoiseSection(const ImuUnitData& d, const ConstantsFile* constants) {
  if (constants == nullptr || !constants->imu) {
    return NotAvailable("Noise",
                        "no constants.json for " + d.serial +
                            " in the fit directory: the noise is read in calibrated units");
  }
  const ImuAcquisition* rest = LongestAtRest(d);
  if (rest == nullptr || rest->samples.size() < kMinRestSamples) {
    return NotAvailable(
        "Noise", fmt::format("no acquisition at rest with at least {} packets", kMinRestSamples));
  }
  const std::vector<ImuSample>& samples = rest->samples;
  const double dt_s =
      (samples.back().t_s - samples.front().t_s) / static_cast<double>(samples.size() - 1);
  if (!(dt_s > 0.0)) {
    return NotAvailable("Noise", "the acquisition's packet times do not advance");
  }
  std::array<std::vector<double>, 6> series;  // A x y z (mg), G x y z (deg/s)
  for (const ImuSample& s : samples) {
    const auto full =
        fm::ImuReference(*constants->imu, fm::ImuCompensationMode::kFullyCalibrated, s.raw);
    for (int i = 0; i < 3; ++i) {
      series[i].push_back(full[i] / kMpsPerMg);
      series[3 + i].push_back(full[3 + i]);
    }
  }
  std::array<AllanTerms, 6> terms;
  for (int i = 0; i < 6; ++i) terms[i] = ReadAllanTerms(series[i], dt_s);

  const std::string record = fmt::format(
      "{}: step {} ({}), orientation {}, {} packets over {} s at rest (mean interval {} s)",
      d.serial,
      rest->step,
      rest->step_kind,
      rest->orientation,
      samples.size(),
      FormatNumber(terms[0].record_s, 4),
      FormatNumber(dt_s, 4));
  std::string html = "<p>" + XmlEscape(record) + "</p>\n";
  for (const bool gyro : {true, false}) {
    Plot plot{fmt::format("{} {} Allan deviation at rest (overlapping, IEEE Std 952)",
                          d.serial,
                          gyro ? "gyro G" : "accelerometer A"),
              "cluster time tau (s)",
              gyro ? "Allan deviation (deg/s)" : "Allan deviation (mg)",
              {},
              {}};
    plot.log_x = plot.log_y = true;
    plot.figure = "allan";
    for (int i = 0; i < 3; ++i) {
      const AllanTerms& t = terms[gyro ? 3 + i : i];
      PlotSeries s{
          fmt::format("{} {}", gyro ? "G" : "A", kAxes[i]), {}, {}, PlotSeries::Style::kLine};
      for (const auto& p : t.curve) {
        s.x.push_back(p.tau_s);
        s.y.push_back(p.adev);
      }
      plot.series.push_back(std::move(s));
    }
    html += RenderSvg(plot);
  }
  HtmlTable gyro_table{d.serial + " gyro noise terms (IEEE Std 952; density one-sided)",
                       {"axis",
                        "white term read at tau (s)",
                        "angle random walk N (deg/sqrt(h))",
                        "rate noise density (deg/s/sqrt(Hz), one-sided)",
                        "bias instability (deg/h)"},
                       {}};
  HtmlTable accel_table{d.serial + " accelerometer noise terms (density one-sided)",
                        {"axis",
                         "white term read at tau (s)",
                         "velocity random walk (m/s/sqrt(h))",
                         "noise density (ug/sqrt(Hz), one-sided)",
                         "bias instability (ug)"},
                        {}};
  for (int i = 0; i < 3; ++i) {
    const AllanTerms& g = terms[3 + i];
    gyro_table.rows.push_back({kAxes[i],
                               TauNote(g),
                               FormatNumber(g.random_walk_per_rts * kSqrtSecondsPerHour, 4),
                               FormatNumber(g.density_one_sided_per_rthz, 4),
                               FloorText(g.bias_instability * kSecondsPerHour, g)});
    const AllanTerms& a = terms[i];  // in mg
    accel_table.rows.push_back(
        {kAxes[i],
         TauNote(a),
         FormatNumber(a.random_walk_per_rts * kMpsPerMg * kSqrtSecondsPerHour, 4),
         FormatNumber(a.density_one_sided_per_rthz * kMpsPerMg / kMpsPerUg, 4),
         FloorText(a.bias_instability * kMpsPerMg / kMpsPerUg, a)});
  }
  return html + RenderTable(gyro_table) + RenderTable(accel_table);
}

}  // namespace adahrs::calib
