#include "diagnosis/imu_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include <fmt/format.h>

#include "common/imu_layout.h"
#include "common/median.h"
#include "diagnosis/clustered_least_squares.h"
#include "diagnosis/held_out_excess.h"
#include "diagnosis/imu_effects.h"
#include "diagnosis/plausible_range.h"
#include "diagnosis/slow_noise.h"
#include "diagnosis/structure_location.h"
#include "diagnosis/term_selection.h"

namespace adahrs::diagnosis {
namespace {

using nlohmann::json;

constexpr double kTempRef_c = 25.0;
constexpr double kTempHalfSpan_c = 62.5;
constexpr double kRateFullScale_dps = 150.0;

// Column indices of the baseline, per channel kind.
enum Baseline { kOffset = 0, kTemp1, kTemp2, kTemp3, kStim0, kStim1, kStim2, kRate2, kRate3 };

struct Candidate {
  Effect effect;
  std::vector<std::string> components;
  std::optional<double> tau_s;
  std::vector<int> columns;  // filled by the layout
};

// What the dependent columns need from the current baseline fit.
struct BaselineState {
  std::array<double, 3> temp{};                    // coefficients of s, s^2, s^3
  Eigen::Vector3d stim = Eigen::Vector3d::Zero();  // m (duty/g) or n (counts per deg/s)
};

struct Layout {
  int channel = 0;
  int baseline = 0;
  std::vector<std::string> names;
  std::vector<Candidate> candidates;
};

const char* EffectName(Effect e) { return EffectRow(e).name; }

Layout MakeLayout(int channel, bool hysteresis) {
  Layout l;
  l.channel = channel;
  const bool gyro = common::IsGyroChannel(channel);
  l.names = {"offset", "temp_s", "temp_s2", "temp_s3"};
  if (gyro) {
    for (const char* n : {"w_x", "w_y", "w_z", "u2", "u3"}) l.names.push_back(n);
  } else {
    for (const char* n : {"f_x", "f_y", "f_z"}) l.names.push_back(n);
  }
  l.baseline = static_cast<int>(l.names.size());
  for (const ImuEffect& e : ImuEffects()) {
    if (!(gyro ? e.on_gyro : e.on_accel) || (e.needs_hysteresis_option && !hysteresis)) continue;
    if (e.taus_s.empty()) l.candidates.push_back({e.effect, e.components(channel), {}, {}});
    for (double tau : e.taus_s) l.candidates.push_back({e.effect, e.components(channel), tau, {}});
  }
  for (Candidate& c : l.candidates) {
    for (const std::string& comp : c.components) {
      c.columns.push_back(static_cast<int>(l.names.size()));
      l.names.push_back(EffectName(c.effect) + (c.tau_s ? fmt::format("_{:.0f}s", *c.tau_s) : "") +
                        "." + comp);
    }
  }
  return l;
}

// Every (channel, effect) test of a unit: the cell model's effects and table_rate_ripple on each
// gyro. An effect's alternatives (the warm-up's time constants) count as one test: they are
// nearly collinear (the clean false-discovery rate in docs/diagnose.md is measured with this
// count).
int CandidateTests(bool hysteresis) {
  int n = 0;
  for (int ch = 0; ch < kImuChannels; ++ch) {
    for (const Candidate& c : MakeLayout(ch, hysteresis).candidates) {
      const std::vector<double>& taus = EffectRow(c.effect).taus_s;
      n += taus.empty() || c.tau_s == taus.front() ? 1 : 0;
    }
    n += common::IsGyroChannel(ch) ? 1 : 0;
  }
  return n;
}

// The design row of one cell for `layout` under `state`.
Eigen::VectorXd Row(const Layout& layout, const DiagnosisCell& c, const BaselineState& state) {
  const int ch = layout.channel;
  const int k = common::kImuChannels[ch].thermometer;
  const bool gyro = common::IsGyroChannel(ch);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(static_cast<int>(layout.names.size()));
  const double s = (c.temp_c[k] - kTempRef_c) / kTempHalfSpan_c;
  x[kOffset] = 1.0;
  x[kTemp1] = s;
  x[kTemp2] = s * s;
  x[kTemp3] = s * s * s;
  const Eigen::Vector3d& stim = gyro ? c.w_B_dps : c.f_B_g;
  for (int j = 0; j < 3; ++j) x[kStim0 + j] = stim[j];
  if (gyro) {
    const double u = c.w_B_dps[common::kImuChannels[ch].axis] / kRateFullScale_dps;
    x[kRate2] = u * u;
    x[kRate3] = u * u * u;
  }
  const double dudt_per_c =
      (state.temp[0] + 2.0 * state.temp[1] * s + 3.0 * state.temp[2] * s * s) / kTempHalfSpan_c;
  const double own_sensitivity = std::abs(state.stim[common::kImuChannels[ch].axis]);
  for (const Candidate& cand : layout.candidates) {
    const EffectInputs in{c,
                          ch,
                          dudt_per_c,
                          c.temp_c[k] - kTempRef_c,
                          stim,
                          state.stim.dot(stim),
                          own_sensitivity,
                          cand.tau_s};
    EffectRow(cand.effect).columns(in, x.data() + cand.columns[0]);
  }
  return x;
}

struct ChannelData {
  std::vector<double> y;  // centred cell means
  double centre = 0.0;
  double offset_ratio =
      std::numeric_limits<double>::infinity();  // sigma_e^2 / sigma_w^2 per row weight
};

ChannelData CentredOutput(const DiagnosisData& data, int ch) {
  ChannelData out;
  double sw = 0.0;
  for (const DiagnosisCell& c : data.cells) {
    out.centre += c.rows * c.y_mean[ch];
    sw += c.rows;
  }
  out.centre /= sw;
  for (const DiagnosisCell& c : data.cells) out.y.push_back(c.y_mean[ch] - out.centre);
  return out;
}

ClusteredLeastSquares Accumulate(const DiagnosisData& data,
                                 const Layout& layout,
                                 const ChannelData& y,
                                 const BaselineState& state) {
  ClusteredLeastSquares ls(static_cast<int>(layout.names.size()),
                           static_cast<int>(data.segments.size()));
  ls.SetClusterOffsetRatio(y.offset_ratio);
  for (size_t i = 0; i < data.cells.size(); ++i) {
    const DiagnosisCell& c = data.cells[i];
    ls.Add(c.segment, Row(layout, c, state), y.y[i], static_cast<double>(c.rows));
  }
  return ls;
}

// The design weighted by white noise alone (no random intercept per segment).
ClusteredLeastSquares AccumulateWhite(const DiagnosisData& data,
                                      const Layout& layout,
                                      ChannelData y,
                                      const BaselineState& state) {
  y.offset_ratio = std::numeric_limits<double>::infinity();
  return Accumulate(data, layout, y, state);
}

double Coefficient(const ClusteredFit& fit, const std::vector<int>& subset, int column) {
  for (size_t i = 0; i < subset.size(); ++i) {
    if (subset[i] == column) return fit.theta[static_cast<int>(i)];
  }
  return 0.0;
}

BaselineState StateFrom(const ClusteredFit& fit, const std::vector<int>& subset) {
  BaselineState st;
  for (int j = 0; j < 3; ++j) st.temp[j] = Coefficient(fit, subset, kTemp1 + j);
  for (int j = 0; j < 3; ++j) st.stim[j] = Coefficient(fit, subset, kStim0 + j);
  return st;
}

// Physical units per raw unit of the channel: mg per duty, deg/s per count.
double PhysicalScale(int ch, const BaselineState& st) {
  const double sens = std::abs(st.stim[common::kImuChannels[ch].axis]);
  if (common::IsGyroChannel(ch)) return 1.0 / (sens > 0.0 ? sens : kGyroDatasheetCountsPerDps);
  return 1000.0 / (sens > 0.0 ? sens : kAccelDatasheetDutyPerG);
}

std::string RmsUnit(int ch) { return common::IsGyroChannel(ch) ? "deg/s" : "mg"; }

TermTest RunTest(const ClusteredLeastSquares& ls,
                 const std::vector<int>& selected,
                 const ClusteredFit& selected_fit,
                 const Candidate& cand) {
  return TestTerm(ls, selected, selected_fit, cand.columns);
}

// Magnitudes of a candidate's components in their physical units.
std::vector<FindingComponent> Components(const Candidate& cand,
                                         const Eigen::VectorXd& theta,
                                         const Eigen::VectorXd& se,
                                         int ch,
                                         double phys) {
  std::vector<FindingComponent> out;
  for (size_t i = 0; i < cand.components.size(); ++i) {
    const int k = static_cast<int>(i);
    const EffectUnit u = EffectRow(cand.effect).unit(i, ch, phys);
    out.push_back({cand.components[i], theta[k] * u.scale, se[k] * u.scale, u.unit});
  }
  return out;
}

std::string Words(const Candidate& cand, const std::vector<FindingComponent>& c, int ch) {
  const std::string thermometer =
      std::string("TEMP ") + "xyz"[common::kImuChannels[ch].thermometer];
  return EffectRow(cand.effect).words(common::kImuChannelNames[ch], thermometer, c, cand.tau_s);
}

// Segments where the term's contribution is largest (mean |x theta| over the segment's cells).
std::vector<std::string> Evidence(const DiagnosisData& data,
                                  const Layout& layout,
                                  const BaselineState& st,
                                  const Candidate& cand,
                                  const Eigen::VectorXd& theta) {
  std::vector<double> sum(data.segments.size(), 0.0), w(data.segments.size(), 0.0);
  for (const DiagnosisCell& c : data.cells) {
    const Eigen::VectorXd x = Row(layout, c, st);
    double v = 0.0;
    for (size_t i = 0; i < cand.columns.size(); ++i)
      v += x[cand.columns[i]] * theta[static_cast<int>(i)];
    sum[c.segment] += c.rows * std::abs(v);
    w[c.segment] += c.rows;
  }
  std::vector<int> order(data.segments.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return sum[a] / std::max(1.0, w[a]) > sum[b] / std::max(1.0, w[b]);
  });
  std::vector<std::string> out;
  for (size_t i = 0; i < order.size() && i < 3; ++i) out.push_back(data.segments[order[i]].label);
  return out;
}

std::vector<double> Residuals(const DiagnosisData& data,
                              const Layout& layout,
                              const BaselineState& st,
                              const ClusteredFit& fit,
                              const std::vector<int>& subset,
                              const ChannelData& y) {
  std::vector<double> r;
  for (size_t i = 0; i < data.cells.size(); ++i) {
    const Eigen::VectorXd x = Row(layout, data.cells[i], st);
    double pred = 0.0;
    for (size_t j = 0; j < subset.size(); ++j)
      pred += x[subset[j]] * fit.theta[static_cast<int>(j)];
    r.push_back(y.y[i] - pred);
  }
  return r;
}

void FillPlot(const DiagnosisData& data,
              const std::vector<double>& base,
              const std::vector<double>& final,
              int ch,
              double phys,
              ChannelFitSummary* out) {
  const size_t stride = std::max<size_t>(1, data.cells.size() / kPlotCells + 1);
  for (size_t i = 0; i < data.cells.size(); i += stride) {
    out->plot_t_s.push_back(data.cells[i].t_mean_s);
    out->plot_temp_c.push_back(data.cells[i].temp_c[common::kImuChannels[ch].thermometer]);
    out->plot_residual_baseline.push_back(base[i] * phys);
    out->plot_residual_final.push_back(final[i] * phys);
  }
}

std::vector<int> BaselineSubset(const ClusteredLeastSquares& ls,
                                const Layout& layout,
                                std::vector<std::string>* notes) {
  std::vector<int> subset;
  for (int j = 0; j < layout.baseline; ++j) {
    std::vector<int> trial = WithColumns(subset, {j});
    if (!ls.FullRank(trial)) {
      notes->push_back(
          fmt::format("{}: baseline term {} is not identifiable from this recording (left out)",
                      common::kImuChannelNames[layout.channel],
                      layout.names[j]));
      continue;
    }
    if (j > kOffset && !ls.Fit(trial).jackknife_ok) {
      notes->push_back(fmt::format("{}: baseline term {} rests on a single segment (left out)",
                                   common::kImuChannelNames[layout.channel],
                                   layout.names[j]));
      continue;
    }
    subset = trial;
  }
  return subset;
}

// sigma_e^2 (per row) from the cell-to-cell differences of the baseline residual within segments,
// sigma_w^2 from the segments' mean residuals beyond it (method of moments on medians, robust to a
// few segments the baseline cannot follow). Their ratio sets the random intercept per segment.
double OffsetRatio(const DiagnosisData& data, const std::vector<double>& residual) {
  std::vector<double> diff, rows;
  std::vector<double> sum(data.segments.size(), 0.0), w(data.segments.size(), 0.0);
  for (size_t i = 0; i < data.cells.size(); ++i) {
    const DiagnosisCell& c = data.cells[i];
    if (i > 0 && data.cells[i - 1].segment == c.segment)
      diff.push_back(std::abs(residual[i] - residual[i - 1]));
    rows.push_back(c.rows);
    sum[c.segment] += c.rows * residual[i];
    w[c.segment] += c.rows;
  }
  if (diff.empty()) return std::numeric_limits<double>::infinity();
  const double sigma_cell = 1.4826 * common::Median(diff) / std::sqrt(2.0);
  const double sigma_e2 = sigma_cell * sigma_cell * common::Median(rows);
  std::vector<double> excess;
  for (size_t s = 0; s < sum.size(); ++s) {
    if (w[s] > 0.0) excess.push_back(std::pow(sum[s] / w[s], 2) - sigma_e2 / w[s]);
  }
  const double sigma_w2 = std::max(0.0, common::Median(excess) / 0.455);
  return sigma_w2 > 0.0 ? sigma_e2 / sigma_w2 : std::numeric_limits<double>::infinity();
}

struct ChannelResult {
  std::vector<Finding> findings;
  std::vector<Unexplained> unexplained;
  std::vector<DetectionLimit> limits;
  ChannelFitSummary summary;
};

// table_rate_ripple, a rig effect measured on the rows (rate_ripple.h), not a column of the cells'
// model: its detection limit always, a finding when the test passes at `alpha`.
void DiagnoseRipple(const DiagnosisData& data,
                    int ch,
                    double phys,
                    double alpha,
                    double power_z,
                    ChannelResult* out) {
  const std::vector<RippleSegment>& segments = data.ripple[static_cast<size_t>(ch - 6)];
  const RippleTest r = TestRipple(segments, 1.0 / phys, alpha, power_z);
  DetectionLimit lim{"table_rate_ripple", common::kImuChannelNames[ch], {}, r.note};
  if (r.testable)
    lim.limits.push_back({"ratio", r.smallest_detectable_ratio * 1e6, 0.0, "ppm of rate"});
  out->limits.push_back(std::move(lim));
  if (!r.testable || r.p_value >= alpha) return;
  double fastest_dps = 0.0;
  for (const RippleSegment& seg : segments)
    fastest_dps = std::max(fastest_dps, std::abs(seg.rate_dps));
  Finding f;
  f.effect = "table_rate_ripple";
  f.channel = common::kImuChannelNames[ch];
  f.components.push_back({"ratio", r.ratio * 1e6, r.ratio_se * 1e6, "ppm of rate"});
  f.wald_p_value = r.p_value;
  f.held_out_rms_before = r.held_out_rms_before_dps;
  f.held_out_rms_after = r.held_out_rms_after_dps;
  f.rms_unit = "deg/s (amplitude at the revolution frequency)";
  for (int seg : r.strongest_segments)
    f.evidence.push_back(data.segments[static_cast<size_t>(seg)].label);
  f.words = fmt::format(
      "{} carries a line at the table's revolution frequency of {:.3g} ± {:.2g} ppm of the rate "
      "({:.3g} deg/s at {:.0f} deg/s, over {} segments): table rate ripple, the table turns "
      "unevenly once per revolution; a rig effect, not the unit's",
      f.channel,
      r.ratio * 1e6,
      r.ratio_se * 1e6,
      r.ratio * fastest_dps,
      fastest_dps,
      r.segments);
  out->findings.push_back(std::move(f));
}

// A channel's model with its baseline fitted: the design under the baseline's state, with the
// random intercept per segment that the baseline's residual sets.
struct ChannelModel {
  Layout layout;
  ChannelData y;
  BaselineState st;
  ClusteredLeastSquares ls;
  ClusteredLeastSquares ls_white;  // the same design without the random intercept
  std::vector<int> base;           // the baseline's identifiable columns
};

ChannelModel FitBaseline(const DiagnosisData& data,
                         int ch,
                         const DiagnosisOptions& options,
                         std::vector<std::string>* notes) {
  Layout layout = MakeLayout(ch, options.thermal_hysteresis_candidate);
  ChannelData y = CentredOutput(data, ch);
  const ClusteredLeastSquares ls0 = Accumulate(data, layout, y, BaselineState{});
  std::vector<int> base = BaselineSubset(ls0, layout, notes);
  const ClusteredFit base_fit0 = ls0.Fit(base);
  if (!base_fit0.ok) {
    throw calib::ImuInputError(data.serial + ": " + common::kImuChannelNames[ch] +
                               ": the baseline cannot be fitted");
  }
  const BaselineState st = StateFrom(base_fit0, base);
  y.offset_ratio = OffsetRatio(data, Residuals(data, layout, st, base_fit0, base, y));
  ClusteredLeastSquares ls = Accumulate(data, layout, y, st);
  ClusteredLeastSquares ls_white = AccumulateWhite(data, layout, y, st);
  return ChannelModel{
      std::move(layout), std::move(y), st, std::move(ls), std::move(ls_white), std::move(base)};
}

// The candidates whose column changes only between long stretches of the recording (the sense of
// the last temperature change, the time since power-on) or between the few input levels the
// capture quantises (f_axis^2 is 0 or 1 under gravity): tested against the recording's own slow
// noise as well as by the jackknife (slow_noise.h).
bool SlowCandidate(Effect e) { return EffectRow(e).slow; }

// Variance of the estimate of column `subset[pos]` in `fit` under the residual's measured wander,
// its white noise and, for the nonlinearity, the capture quantiser's bias per input level: an
// offset per segment uniform over one output step (the edges' tick phase repeats while the input
// holds still, so the bias need not average away).
double SlowVariance(const DiagnosisData& data,
                    const ChannelModel& m,
                    const ClusteredLeastSquares& ls,
                    const std::vector<int>& subset,
                    const ClusteredFit& fit,
                    size_t pos,
                    const Candidate& cand) {
  const int ch = m.layout.channel;
  const Eigen::MatrixXd info = ls.Information(subset);
  const Eigen::VectorXd d = info.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  Eigen::VectorXd e = Eigen::VectorXd::Zero(static_cast<int>(subset.size()));
  e[static_cast<int>(pos)] = 1.0;
  const Eigen::MatrixXd scaled = d.asDiagonal() * info * d.asDiagonal();
  const Eigen::VectorXd g = d.asDiagonal() * scaled.ldlt().solve(d.asDiagonal() * e);
  std::vector<Eigen::VectorXd> shrink;
  for (size_t sgm = 0; sgm < data.segments.size(); ++sgm)
    shrink.push_back(ls.ClusterShrink(static_cast<int>(sgm), subset));
  const std::vector<double> r = Residuals(data, m.layout, m.st, fit, subset, m.y);
  std::vector<SlowNoiseCell> cells;
  Eigen::VectorXd xs(static_cast<int>(subset.size()));
  for (size_t i = 0; i < data.cells.size(); ++i) {
    const DiagnosisCell& c = data.cells[i];
    const Eigen::VectorXd x = Row(m.layout, c, m.st);
    for (size_t j = 0; j < subset.size(); ++j) xs[static_cast<int>(j)] = x[subset[j]];
    const double a = c.rows * g.dot(xs - shrink[static_cast<size_t>(c.segment)]);
    cells.push_back({c.run, c.segment, c.t_mean_s, r[i], c.y_var[ch] / std::max(1, c.rows), a});
  }
  const double q = data.output_quantum[ch];
  const double offset_var = EffectRow(cand.effect).quantised_input ? q * q / 12.0 : 0.0;
  return SlowNoiseVariance(cells, offset_var);
}

// The dependent columns rebuilt from the final baseline once, kept when their fit holds.
void RebuildFromFinalBaseline(const DiagnosisData& data, ChannelModel& m, TermSelection& sel) {
  const BaselineState refined = StateFrom(sel.fit, sel.selected);
  ClusteredLeastSquares ls2 = Accumulate(data, m.layout, m.y, refined);
  ClusteredFit fit2 = ls2.Fit(sel.selected);
  if (fit2.ok && fit2.jackknife_ok) {
    m.st = refined;
    m.ls = std::move(ls2);
    m.ls_white = AccumulateWhite(data, m.layout, m.y, refined);
    sel.fit = std::move(fit2);
  }
}

// A cross-axis coupling's change with temperature needs the cross-axis input at temperatures
// apart: the temperature span of the cells whose off-axis input is at least half its largest must
// reach kMinCrossAxisSpan_c (within a soak's few tenths of a degree, the column is the input times
// the thermometer's noise).
constexpr double kMinCrossAxisSpan_c = 10.0;

bool CrossAxisExcited(const DiagnosisData& data, int ch) {
  const bool gyro = common::IsGyroChannel(ch);
  const int k = common::kImuChannels[ch].thermometer;
  for (int j = 0; j < 3; ++j) {
    if (j == common::kImuChannels[ch].axis) continue;
    double largest = 0.0;
    for (const DiagnosisCell& c : data.cells)
      largest = std::max(largest, std::abs(gyro ? c.w_B_dps[j] : c.f_B_g[j]));
    double lo = 1e9, hi = -1e9;
    for (const DiagnosisCell& c : data.cells) {
      if (!(largest > 0.0) || std::abs(gyro ? c.w_B_dps[j] : c.f_B_g[j]) < 0.5 * largest) continue;
      lo = std::min(lo, c.temp_c[k]);
      hi = std::max(hi, c.temp_c[k]);
    }
    if (hi - lo >= kMinCrossAxisSpan_c) return true;
  }
  return false;
}

// The system a candidate is tested and sized in. The slow candidates are contrasts between
// stretches of the recording: the random intercept per segment, measured on the baseline's
// residual, would hold the very contrast they are (a thermal hysteresis is an offset per segment
// set by the sense of the last change) and take it from them; they are weighted by white noise
// alone, and their variance is the recording's measured slow wander (SlowVariance) where it
// exceeds the jackknife's.
const ClusteredLeastSquares& SystemFor(const ChannelModel& m, const Candidate& cand) {
  return SlowCandidate(cand.effect) ? m.ls_white : m.ls;
}

// Forward selection over the layout's candidates, at most one per effect (one warm-up time
// constant of several), the cross-axis tempco only when `cross_excited` (CrossAxisExcited); the
// slow candidates are tested in m.ls_white (SystemFor); `chosen` indexes m.layout.candidates.
TermSelection SelectCandidates(const DiagnosisData& data,
                               ChannelModel& m,
                               bool cross_excited,
                               double alpha,
                               int max_findings) {
  const std::vector<Candidate>& candidates = m.layout.candidates;
  std::vector<std::vector<int>> columns;
  for (const Candidate& c : candidates) columns.push_back(c.columns);
  const auto one_per_effect = [&](int k, const std::vector<int>& chosen) {
    if (EffectRow(candidates[static_cast<size_t>(k)].effect).needs_cross_excitation &&
        !cross_excited)
      return false;
    return std::none_of(chosen.begin(), chosen.end(), [&](int c) {
      return candidates[static_cast<size_t>(c)].effect == candidates[static_cast<size_t>(k)].effect;
    });
  };
  const auto slow_noise = [&](int k, TermTest* t) {
    const Candidate& c = candidates[static_cast<size_t>(k)];
    if (!SlowCandidate(c.effect)) return;
    FloorCandidateVariance(
        SlowVariance(data, m, SystemFor(m, c), t->subset, t->fit, t->subset.size() - 1, c), t);
  };
  const auto slow = [&](int k) { return SlowCandidate(candidates[static_cast<size_t>(k)].effect); };
  TermSelection sel = SelectTerms(m.ls,
                                  m.base,
                                  m.ls.Fit(m.base),
                                  columns,
                                  alpha,
                                  max_findings,
                                  one_per_effect,
                                  slow_noise,
                                  &m.ls_white,
                                  slow);
  if (!sel.chosen.empty()) RebuildFromFinalBaseline(data, m, sel);
  return sel;
}

Finding ChosenFinding(const DiagnosisData& data,
                      const ChannelModel& m,
                      const TermSelection& sel,
                      const Candidate& cand,
                      double phys) {
  const int ch = m.layout.channel;
  const ClusteredLeastSquares& ls = SystemFor(m, cand);
  const std::vector<int> without = WithoutColumns(sel.selected, cand.columns);
  const ClusteredFit fit_without = ls.Fit(without);
  const ClusteredFit fit_with = SlowCandidate(cand.effect) ? ls.Fit(sel.selected) : sel.fit;
  Eigen::VectorXd theta, se;
  ColumnEstimates(fit_with, sel.selected, cand.columns, &theta, &se);
  TermTest test = RunTest(ls, without, fit_without, cand);
  if (SlowCandidate(cand.effect)) {
    const size_t pos =
        static_cast<size_t>(std::find(sel.selected.begin(), sel.selected.end(), cand.columns[0]) -
                            sel.selected.begin());
    se[0] =
        std::max(se[0], std::sqrt(SlowVariance(data, m, ls, sel.selected, fit_with, pos, cand)));
    FloorCandidateVariance(
        SlowVariance(data, m, ls, test.subset, test.fit, test.subset.size() - 1, cand), &test);
  }
  Finding f;
  f.effect = EffectName(cand.effect);
  f.channel = common::kImuChannelNames[ch];
  f.components = Components(cand, theta, se, ch, phys);
  f.time_constant_s = cand.tau_s;
  f.held_out_rms_before = HeldOutRms(fit_without, fit_with, false, phys);
  f.held_out_rms_after = HeldOutRms(fit_without, fit_with, true, phys);
  f.rms_unit = RmsUnit(ch);
  f.evidence = Evidence(data, m.layout, m.st, cand, theta);
  f.words = Words(cand, f.components, ch);
  f.wald_p_value = test.p_value;
  return f;
}

// Time from the first cell to the last, s (a delay longer than that is not seen as one).
double RecordingDuration(const DiagnosisData& data) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const DiagnosisCell& c : data.cells) {
    lo = std::min(lo, c.t_mean_s);
    hi = std::max(hi, c.t_mean_s);
  }
  return hi > lo ? hi - lo : 0.0;
}

// The smallest size of the candidate's components the test would find with power_z, or why the
// recording cannot test it (`cross_excited` as for SelectCandidates).
DetectionLimit CandidateLimit(const DiagnosisData& data,
                              const ChannelModel& m,
                              const TermSelection& sel,
                              const Candidate& cand,
                              bool cross_excited,
                              double tcrit,
                              double power_z,
                              double phys) {
  const int ch = m.layout.channel;
  DetectionLimit lim;
  lim.effect =
      EffectName(cand.effect) + (cand.tau_s ? fmt::format(" (tau_w {:.0f} s)", *cand.tau_s) : "");
  lim.channel = common::kImuChannelNames[ch];
  Eigen::VectorXd se;
  if (EffectRow(cand.effect).needs_cross_excitation && !cross_excited) {
    lim.note = fmt::format("not excited: the cross-axis input spans less than {:.0f} degC",
                           kMinCrossAxisSpan_c);
    return lim;
  }
  const ClusteredLeastSquares& ls = SystemFor(m, cand);
  if (!LimitStandardErrors(ls, sel.selected, cand.columns, &se, &lim.note)) return lim;
  if (SlowCandidate(cand.effect)) {
    const std::vector<int> subset =
        WithColumns(WithoutColumns(sel.selected, cand.columns), cand.columns);
    const double v = SlowVariance(data, m, ls, subset, ls.Fit(subset), subset.size() - 1, cand);
    se[0] = std::max(se[0], std::sqrt(v));
  }
  const Eigen::VectorXd limit = se * (tcrit + power_z);
  lim.limits = Components(cand, limit, se, ch, phys);
  for (FindingComponent& c : lim.limits) c.magnitude = std::abs(c.magnitude);
  lim.note = NotTestableReason(lim.limits, RecordingDuration(data));
  if (!lim.note.empty()) lim.limits.clear();
  return lim;
}

ChannelFitSummary FitSummary(const DiagnosisData& data,
                             const ChannelModel& m,
                             const ClusteredFit& base_fit,
                             const ClusteredFit& final_fit,
                             double phys) {
  const int ch = m.layout.channel;
  std::vector<double> white;
  for (const DiagnosisCell& c : data.cells)
    white.push_back(std::sqrt(c.y_var[ch] / std::max(1, c.rows)));
  ChannelFitSummary summary;
  summary.channel = common::kImuChannelNames[ch];
  summary.unit = RmsUnit(ch);
  summary.held_out_rms_baseline = HeldOutRms(base_fit, final_fit, false, phys);
  summary.held_out_rms_final = HeldOutRms(base_fit, final_fit, true, phys);
  summary.white_noise_rms = common::Median(white) * phys;
  for (int col : m.base) summary.baseline_terms.push_back(m.layout.names[col]);
  return summary;
}

ChannelResult DiagnoseChannel(const DiagnosisData& data,
                              int ch,
                              const DiagnosisOptions& options,
                              double alpha,
                              std::vector<std::string>* notes) {
  ChannelModel m = FitBaseline(data, ch, options, notes);
  const bool cross_excited = CrossAxisExcited(data, ch);
  const TermSelection sel =
      SelectCandidates(data, m, cross_excited, alpha, options.max_findings_per_channel);
  const double phys = PhysicalScale(ch, m.st);
  const double tcrit = TCritical(alpha, sel.fit.clusters);
  ChannelResult out;
  for (int k : sel.chosen) {
    out.findings.push_back(
        ChosenFinding(data, m, sel, m.layout.candidates[static_cast<size_t>(k)], phys));
  }
  for (const Candidate& cand : m.layout.candidates) {
    out.limits.push_back(
        CandidateLimit(data, m, sel, cand, cross_excited, tcrit, options.power_z, phys));
  }
  const ClusteredFit base_fit = m.ls.Fit(m.base);
  out.summary = FitSummary(data, m, base_fit, sel.fit, phys);
  std::vector<std::string> labels;
  for (const DiagnosisSegment& s : data.segments) labels.push_back(s.label);
  if (auto excess = HeldOutExcess(out.summary, sel.fit, labels, phys))
    out.unexplained.push_back(std::move(*excess));
  const std::vector<double> residual = Residuals(data, m.layout, m.st, sel.fit, sel.selected, m.y);
  FillPlot(data,
           Residuals(data, m.layout, m.st, base_fit, m.base, m.y),
           residual,
           ch,
           phys,
           &out.summary);
  LocateStructure(data, ch, residual, phys, RmsUnit(ch), &out.unexplained, notes);
  LocatePeriodic(
      data, ch, options.family_alpha / kImuChannels, phys, RmsUnit(ch), &out.unexplained, notes);
  if (common::IsGyroChannel(ch)) DiagnoseRipple(data, ch, phys, alpha, options.power_z, &out);
  return out;
}

}  // namespace

UnitDiagnosis DiagnoseImu(const DiagnosisData& data, const DiagnosisOptions& options) {
  UnitDiagnosis out;
  out.serial = data.serial;
  out.rows = data.rows;
  out.segments = static_cast<int>(data.segments.size());
  out.cells = static_cast<int>(data.cells.size());
  out.temp_span_c = data.temp_span_c;
  out.thermometers_fitted =
      data.thermometers[0].fitted && data.thermometers[1].fitted && data.thermometers[2].fitted;
  if (!out.thermometers_fitted) {
    out.notes.push_back(
        "the recording's soaks span less than 5 degC: thermometers use the datasheet's 110.1 "
        "counts/degC");
  }
  out.notes.push_back(data.seq_gaps == 0
                          ? "sequence counter: no packet missing inside a segment"
                          : fmt::format("sequence counter: {} gap(s) inside segments, {} packet(s) "
                                        "missing (the largest, {}, at t = {:.2f} s; "
                                        "a gap of 256 or more is counted modulo 256); cells close "
                                        "at a gap in time, nothing is interpolated",
                                        data.seq_gaps,
                                        data.seq_missing,
                                        data.largest_seq_gap,
                                        data.largest_seq_gap_at_s));
  out.notes.push_back(
      data.spectra.windows() == 0
          ? fmt::format(
                "row spectra: no run of {} rows at a steady interval: periodic lines not searched",
                data.spectra.window_rows())
          : fmt::format("row spectra: {} windows of {} rows at {:.4g} s (bins of {:.3g} Hz)",
                        data.spectra.windows(),
                        data.spectra.window_rows(),
                        data.spectra.dt_s(),
                        data.spectra.BinHz(1.0)));
  out.tests = CandidateTests(options.thermal_hysteresis_candidate);
  out.test_alpha = options.family_alpha / out.tests;
  for (int ch = 0; ch < kImuChannels; ++ch) {
    ChannelResult r = DiagnoseChannel(data, ch, options, out.test_alpha, &out.notes);
    for (Finding& f : r.findings) out.findings.push_back(std::move(f));
    for (Unexplained& u : r.unexplained) out.unexplained.push_back(std::move(u));
    for (DetectionLimit& l : r.limits) out.detection_limits.push_back(std::move(l));
    out.channels.push_back(std::move(r.summary));
  }
  return out;
}

}  // namespace adahrs::diagnosis
