#include "diagnosis/channel_diagnosis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include <fmt/format.h>
#include <boost/math/distributions/fisher_f.hpp>

#include "common/median.h"
#include "diagnosis/clustered_least_squares.h"
#include "diagnosis/held_out_excess.h"
#include "diagnosis/last_change_sense.h"
#include "diagnosis/plausible_range.h"
#include "diagnosis/row_spectrum.h"
#include "diagnosis/term_selection.h"

namespace adahrs::diagnosis {
namespace {

constexpr double kCell_s = 1.0;
constexpr double kMinRateWindow_s = 30.0;
constexpr int kMaxBiasDegree = 3;
constexpr int kMinSegments = 3;
// A lag or warm-up acts through the bias's change with temperature: unless the bias polynomial's
// temperature terms are jointly significant at this level, they are not testable here.
constexpr double kBiasChangeLevel = 0.01;
constexpr std::array<double, 4> kWarmUpTau_s = {150.0, 300.0, 600.0, 1200.0};
enum Candidate { kLag = 0, kHysteresis = 1, kWarmUp0 = 2 };
constexpr int kCandidates = 2 + static_cast<int>(kWarmUpTau_s.size());

struct Cell {
  int segment = 0;
  int rows = 0;
  double t_s = 0, temp_c = 0, rate_c_per_s = 0, sense = 0, since_s = 0;
  std::vector<double> y, var, x;  // outputs' means and variances, references' means
};

struct Prepared {
  std::vector<Cell> cells;
  std::vector<std::string> labels;
  std::vector<std::pair<size_t, size_t>> segment_rows;  // [first, end) per segment
  double t_mid = 0, t_half = 1, span_c = 0;
  bool both_senses = false;  ///< the temperature rose and fell: thermal hysteresis can be seen
};

// Mean and sample variance of v[a..b), about v[a] (raw counts can be large).
void MeanVar(const std::vector<double>& v, size_t a, size_t b, double* mean, double* var) {
  double s = 0, s2 = 0;
  for (size_t i = a; i < b; ++i) {
    const double d = v[i] - v[a];
    s += d;
    s2 += d * d;
  }
  const double n = static_cast<double>(b - a);
  *mean = v[a] + s / n;
  *var = n > 1 ? std::max(0.0, (s2 - s * s / n) / (n - 1)) : 0.0;
}

Cell MakeCell(const ChannelRecording& r, int segment, size_t a, size_t b) {
  Cell c;
  c.segment = segment;
  c.rows = static_cast<int>(b - a);
  double v = 0;
  MeanVar(r.t_s, a, b, &c.t_s, &v);
  MeanVar(r.temp_c, a, b, &c.temp_c, &v);
  for (const ChannelSeries& o : r.outputs) {
    double m = 0, var = 0;
    MeanVar(o.values, a, b, &m, &var);
    c.y.push_back(m);
    c.var.push_back(var);
  }
  for (const ChannelSeries& x : r.references) {
    double m = 0;
    MeanVar(x.values, a, b, &m, &v);
    c.x.push_back(m);
  }
  c.since_s = c.t_s - r.t_s.front();
  return c;
}

void Segment(const ChannelRecording& r, Prepared* p) {
  const double max_gap = r.max_gap_s > 0.0 ? r.max_gap_s : 10.0 * MedianInterval(r.t_s);
  size_t seg_start = 0;
  for (size_t i = 1; i <= r.t_s.size(); ++i) {
    const bool end = i == r.t_s.size() || r.t_s[i] - r.t_s[i - 1] > max_gap ||
                     r.t_s[i] - r.t_s[seg_start] >= r.segment_s;
    if (!end) continue;
    const int segment = static_cast<int>(p->segment_rows.size());
    p->segment_rows.emplace_back(seg_start, i);
    size_t cell_start = seg_start;
    for (size_t k = seg_start + 1; k <= i; ++k) {
      if (k == i || r.t_s[k] - r.t_s[cell_start] >= kCell_s) {
        p->cells.push_back(MakeCell(r, segment, cell_start, k));
        cell_start = k;
      }
    }
    p->labels.push_back(fmt::format("segment {} (t = {:.0f}-{:.0f} s, {:.1f} degC)",
                                    segment + 1,
                                    r.t_s[seg_start],
                                    r.t_s[i - 1],
                                    r.temp_c[seg_start]));
    seg_start = i;
  }
}

// Temperature rate per cell (slope within +-W) and the sense of the last change (causal).
void ThermalState(Prepared* p) {
  std::vector<double> starts;
  for (const Cell& c : p->cells) {
    if (starts.empty() || c.segment != p->cells[&c - p->cells.data() - 1].segment)
      starts.push_back(c.t_s);
  }
  std::vector<double> spacing;
  for (size_t i = 1; i < starts.size(); ++i) spacing.push_back(starts[i] - starts[i - 1]);
  const double w = std::max(kMinRateWindow_s, 1.1 * common::Median(spacing));
  size_t lo = 0, hi = 0;
  LastChangeSense sense;
  for (Cell& c : p->cells) {
    while (p->cells[lo].t_s < c.t_s - w) ++lo;
    while (hi + 1 < p->cells.size() && p->cells[hi + 1].t_s <= c.t_s + w) ++hi;
    double sw = 0, st = 0, sv = 0, stt = 0, stv = 0;
    for (size_t j = lo; j <= hi; ++j) {
      const double wt = p->cells[j].rows, dt = p->cells[j].t_s - c.t_s, v = p->cells[j].temp_c;
      sw += wt;
      st += wt * dt;
      sv += wt * v;
      stt += wt * dt * dt;
      stv += wt * dt * v;
    }
    const double den = sw * stt - st * st;
    c.rate_c_per_s = den > 0.0 ? (sw * stv - st * sv) / den : 0.0;
    c.sense = sense.Next(c.temp_c);
  }
}

Prepared Prepare(const ChannelRecording& r) {
  Prepared p;
  Segment(r, &p);
  if (static_cast<int>(p.segment_rows.size()) < kMinSegments) {
    throw ChannelInputError(fmt::format(
        "{}: {} segment(s) in {:.4g} s of rows; diagnosis needs at least {} to hold one out. The "
        "segment cut is the reason: segments are cut every {:.4g} s (sidecar 'segment_s') and at "
        "gaps longer than {:.4g} s ('max_gap_s'); a shorter segment_s gives more",
        r.csv,
        p.segment_rows.size(),
        r.t_s.back() - r.t_s.front(),
        kMinSegments,
        r.segment_s,
        r.max_gap_s > 0.0 ? r.max_gap_s : 10.0 * MedianInterval(r.t_s)));
  }
  ThermalState(&p);
  bool rose = false, fell = false;
  for (const Cell& c : p.cells) {
    rose = rose || c.sense > 0.0;
    fell = fell || c.sense < 0.0;
  }
  p.both_senses = rose && fell;
  const auto [lo, hi] = std::minmax_element(r.temp_c.begin(), r.temp_c.end());
  p.t_mid = 0.5 * (*lo + *hi);
  p.t_half = std::max(0.5 * (*hi - *lo), 0.5);
  p.span_c = *hi - *lo;
  return p;
}

// Columns: bias s^0..s^3, each reference x and x s, then the candidates.
struct Columns {
  int refs = 0;
  int Bias(int k) const { return k; }
  int Ref(int r, int k) const { return kMaxBiasDegree + 1 + 2 * r + k; }
  int Cand(int k) const { return kMaxBiasDegree + 1 + 2 * refs + k; }
  int count() const { return Cand(kCandidates); }
};

Eigen::VectorXd Row(const Columns& cols,
                    const Prepared& p,
                    const Cell& c,
                    const std::array<double, 4>& bias) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(cols.count());
  const double s = (c.temp_c - p.t_mid) / p.t_half;
  for (int k = 0; k <= kMaxBiasDegree; ++k) x[cols.Bias(k)] = std::pow(s, k);
  for (int r = 0; r < cols.refs; ++r) {
    x[cols.Ref(r, 0)] = c.x[static_cast<size_t>(r)];
    x[cols.Ref(r, 1)] = c.x[static_cast<size_t>(r)] * s;
  }
  const double du_dt = (bias[1] + 2 * bias[2] * s + 3 * bias[3] * s * s) / p.t_half;  // per degC
  x[cols.Cand(kLag)] = -du_dt * c.rate_c_per_s;
  x[cols.Cand(kHysteresis)] = p.both_senses ? c.sense : 0.0;  // one sense only: not excited
  for (size_t k = 0; k < kWarmUpTau_s.size(); ++k) {
    x[cols.Cand(kWarmUp0 + static_cast<int>(k))] = du_dt * std::exp(-c.since_s / kWarmUpTau_s[k]);
  }
  return x;
}

ClusteredLeastSquares Accumulate(const Columns& cols,
                                 const Prepared& p,
                                 int out,
                                 const std::array<double, 4>& bias) {
  ClusteredLeastSquares ls(cols.count(), static_cast<int>(p.segment_rows.size()));
  for (const Cell& c : p.cells)
    ls.Add(c.segment, Row(cols, p, c, bias), c.y[static_cast<size_t>(out)], c.rows);
  return ls;
}

std::vector<int> BaseColumns(const Columns& cols, int degree) {
  std::vector<int> base;
  for (int k = 0; k <= degree; ++k) base.push_back(cols.Bias(k));
  for (int r = 0; r < cols.refs; ++r) {
    base.push_back(cols.Ref(r, 0));
    base.push_back(cols.Ref(r, 1));
  }
  return base;
}

std::array<double, 4> BiasOf(const ClusteredFit& fit, const std::vector<int>& subset) {
  std::array<double, 4> b{};
  for (size_t i = 0; i < subset.size(); ++i) {
    if (subset[i] <= kMaxBiasDegree)
      b[static_cast<size_t>(subset[i])] = fit.theta[static_cast<int>(i)];
  }
  return b;
}

std::string EffectName(int k) {
  if (k == kLag) return "thermal_lag";
  if (k == kHysteresis) return "thermal_hysteresis";
  return "self_heating_warm_up";
}

std::vector<FindingComponent> Components(int k,
                                         const Eigen::VectorXd& theta,
                                         const Eigen::VectorXd& se,
                                         const std::string& unit) {
  if (k == kLag) return {{"delay", theta[0], se[0], "s"}};
  if (k == kHysteresis) return {{"half_loop", theta[0], se[0], unit}};
  return {{"initial_excess", theta[0], se[0], "degC"}};
}

std::string Words(int k, const std::vector<FindingComponent>& c, const std::string& name) {
  const std::string v =
      fmt::format("{:.3g} ± {:.2g} {}", c[0].magnitude, c[0].standard_error, c[0].unit);
  if (k == kLag) {
    return fmt::format(
        "{} follows the temperature {} late: thermal lag between the sensing element and the "
        "thermometer is missing from the model",
        name,
        v);
  }
  if (k == kHysteresis) {
    return fmt::format(
        "{} reads {} higher after heating than after cooling (half the loop): thermal hysteresis "
        "is "
        "missing from the model",
        name,
        v);
  }
  return fmt::format(
      "{}'s element starts {} above the thermometer at the first row and settles with tau ≈ {:.0f} "
      "s: "
      "self-heating warm-up is missing from the model",
      name,
      v,
      kWarmUpTau_s[static_cast<size_t>(k - kWarmUp0)]);
}

// The bias's slope against temperature under the linear law, unit per degC, and its jackknife
// standard error; false when the temperatures do not tell it.
bool LinearBiasSlope(const Columns& cols,
                     const Prepared& p,
                     const ClusteredLeastSquares& ls,
                     double* slope,
                     double* se) {
  const std::vector<int> linear = BaseColumns(cols, 1);
  if (!ls.FullRank(linear)) return false;
  const ClusteredFit fit = ls.Fit(linear);
  if (!fit.ok || !fit.jackknife_ok) return false;
  *slope = fit.theta[1] / p.t_half;
  *se = std::sqrt(fit.covariance(1, 1)) / p.t_half;
  return true;
}

// p-value of the bias polynomial's temperature terms in `base` (jackknife Wald against
// F(degree, C-1)); 1 when there are none.
double BiasChangeP(const ClusteredLeastSquares& ls, const std::vector<int>& base, int degree) {
  if (degree < 1) return 1.0;
  const ClusteredFit fit = ls.Fit(base);
  if (!fit.ok || !fit.jackknife_ok) return 1.0;
  const Eigen::VectorXd theta = fit.theta.segment(1, degree);
  const Eigen::MatrixXd v = fit.covariance.block(1, 1, degree, degree);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(v);
  if (ldlt.info() != Eigen::Success || !(v.diagonal().minCoeff() > 0.0)) return 1.0;
  const double wald = theta.dot(ldlt.solve(theta));
  if (!std::isfinite(wald) || wald < 0.0) return 1.0;
  const boost::math::fisher_f dist(degree, std::max(1, fit.clusters - 1));
  return boost::math::cdf(boost::math::complement(dist, wald / degree));
}

// The candidate's detection limit added alone to `selected`, or why the recording cannot test it:
// its term is not excited, or the smallest magnitude it would find is beyond what the effect can
// physically be (plausible_range.h).
DetectionLimit CandidateLimit(const ChannelRecording& rec,
                              const ClusteredLeastSquares& ls,
                              const std::vector<int>& selected,
                              const std::vector<int>& columns,
                              int k,
                              double tcrit,
                              double power_z,
                              const ChannelSeries& series,
                              const std::string& slope_words,
                              double bias_change_p) {
  DetectionLimit lim;
  lim.effect =
      EffectName(k) + (k >= kWarmUp0 ? fmt::format(" (tau_w {:.0f} s)",
                                                   kWarmUpTau_s[static_cast<size_t>(k - kWarmUp0)])
                                     : "");
  lim.channel = series.name;
  Eigen::VectorXd se;
  if (!LimitStandardErrors(ls, selected, columns, &se, &lim.note)) return lim;
  if (k != kHysteresis && bias_change_p > kBiasChangeLevel) {
    lim.note = fmt::format(
        "not testable here: the bias does not change measurably with temperature (its temperature "
        "terms jointly p = {:.2g}, above {:g}); {}",
        bias_change_p,
        kBiasChangeLevel,
        slope_words);
    return lim;
  }
  lim.limits = Components(k, se * (tcrit + power_z), se, series.unit);
  for (FindingComponent& c : lim.limits) c.magnitude = std::abs(c.magnitude);
  lim.note = NotTestableReason(lim.limits, rec.t_s.back() - rec.t_s.front());
  if (!lim.note.empty()) {
    lim.limits.clear();
    if (k != kHysteresis) lim.note += "; " + slope_words;  // a lag or warm-up acts through it
  }
  return lim;
}

struct OutputResult {
  std::vector<Finding> findings;
  std::vector<Unexplained> unexplained;
  std::vector<DetectionLimit> limits;
  ChannelFitSummary summary;
};

// The bias degree (0: none) with the smallest leave-one-segment-out error.
int ChooseDegree(const Columns& cols,
                 const ClusteredLeastSquares& ls,
                 std::vector<std::string>* notes,
                 const std::string& name) {
  int best = -1;
  double best_ss = 0.0;
  for (int d = 0; d <= kMaxBiasDegree; ++d) {
    const std::vector<int> base = BaseColumns(cols, d);
    if (!ls.FullRank(base)) continue;
    const ClusteredFit fit = ls.Fit(base);
    if (!fit.ok || !fit.jackknife_ok) continue;
    const double ss = std::accumulate(fit.held_out_ss.begin(), fit.held_out_ss.end(), 0.0);
    if (std::isfinite(ss) && (best < 0 || ss < best_ss)) {
      best = d;
      best_ss = ss;
    }
  }
  if (best < 0)
    throw ChannelInputError(name +
                            ": no bias polynomial in temperature can be fitted and held out");
  notes->push_back(fmt::format(
      "{}: bias of degree {} in temperature (least leave-one-segment-out error)", name, best));
  return best;
}

std::vector<double> Residuals(const Columns& cols,
                              const Prepared& p,
                              int out,
                              const std::array<double, 4>& bias,
                              const ClusteredFit& fit,
                              const std::vector<int>& subset) {
  std::vector<double> r;
  for (const Cell& c : p.cells) {
    const Eigen::VectorXd x = Row(cols, p, c, bias);
    double pred = 0.0;
    for (size_t k = 0; k < subset.size(); ++k)
      pred += x[subset[k]] * fit.theta[static_cast<int>(k)];
    r.push_back(c.y[static_cast<size_t>(out)] - pred);
  }
  return r;
}

OutputResult DiagnoseOutput(const ChannelRecording& rec,
                            const Prepared& p,
                            int out,
                            double alpha,
                            const DiagnosisOptions& options,
                            std::vector<std::string>* notes) {
  const ChannelSeries& series = rec.outputs[static_cast<size_t>(out)];
  const Columns cols{static_cast<int>(rec.references.size())};
  ClusteredLeastSquares ls = Accumulate(cols, p, out, {});
  const int degree = ChooseDegree(cols, ls, notes, series.name);
  const std::vector<int> base = BaseColumns(cols, degree);
  std::array<double, 4> bias = BiasOf(ls.Fit(base), base);
  ls = Accumulate(cols, p, out, bias);
  std::vector<std::vector<int>> candidates;
  for (int k = 0; k < kCandidates; ++k) candidates.push_back({cols.Cand(k)});
  auto one_warm_up = [](int k, const std::vector<int>& chosen) {
    return k < kWarmUp0 ||
           std::none_of(chosen.begin(), chosen.end(), [](int c) { return c >= kWarmUp0; });
  };
  const double bias_change_p = BiasChangeP(ls, base, degree);
  double slope = 0.0, slope_se = 0.0;
  const bool has_slope = LinearBiasSlope(cols, p, ls, &slope, &slope_se);
  const std::string slope_words =
      has_slope ? fmt::format(
                      "the bias's slope against temperature is {:.3g} ± {:.2g} {}/degC, "
                      "and a lag or warm-up acts only through it",
                      slope,
                      slope_se,
                      series.unit)
                : "the temperatures do not tell the bias's slope";
  // A candidate the recording cannot test (its limit beyond physics) is never a finding.
  const double tcrit_base = TCritical(alpha, ls.Fit(base).clusters);
  std::vector<bool> testable;
  for (int k = 0; k < kCandidates; ++k) {
    testable.push_back(!CandidateLimit(rec,
                                       ls,
                                       base,
                                       candidates[static_cast<size_t>(k)],
                                       k,
                                       tcrit_base,
                                       options.power_z,
                                       series,
                                       slope_words,
                                       bias_change_p)
                            .limits.empty());
  }
  const auto allowed = [&](int k, const std::vector<int>& chosen) {
    return testable[static_cast<size_t>(k)] && one_warm_up(k, chosen);
  };
  TermSelection sel = SelectTerms(
      ls, base, ls.Fit(base), candidates, alpha, options.max_findings_per_channel, allowed);
  if (!sel.chosen.empty()) {  // the dependent columns rebuilt from the final bias once
    const std::array<double, 4> refined = BiasOf(sel.fit, sel.selected);
    ClusteredLeastSquares ls2 = Accumulate(cols, p, out, refined);
    ClusteredFit fit2 = ls2.Fit(sel.selected);
    if (fit2.ok && fit2.jackknife_ok) {
      bias = refined;
      ls = std::move(ls2);
      sel.fit = std::move(fit2);
    }
  }
  OutputResult r;
  for (int k : sel.chosen) {
    const std::vector<int> without =
        WithoutColumns(sel.selected, candidates[static_cast<size_t>(k)]);
    const ClusteredFit fit_without = ls.Fit(without);
    Eigen::VectorXd theta, se;
    ColumnEstimates(sel.fit, sel.selected, candidates[static_cast<size_t>(k)], &theta, &se);
    Finding f;
    f.effect = EffectName(k);
    f.channel = series.name;
    f.components = Components(k, theta, se, series.unit);
    if (k >= kWarmUp0) f.time_constant_s = kWarmUpTau_s[static_cast<size_t>(k - kWarmUp0)];
    f.held_out_rms_before = HeldOutRms(fit_without, sel.fit, false, 1.0);
    f.held_out_rms_after = HeldOutRms(fit_without, sel.fit, true, 1.0);
    f.rms_unit = series.unit;
    f.words = Words(k, f.components, series.name);
    f.wald_p_value = TestTerm(ls, without, fit_without, candidates[static_cast<size_t>(k)]).p_value;
    r.findings.push_back(std::move(f));
  }
  const double tcrit = TCritical(alpha, sel.fit.clusters);
  for (int k = 0; k < kCandidates; ++k) {
    r.limits.push_back(CandidateLimit(rec,
                                      ls,
                                      sel.selected,
                                      candidates[static_cast<size_t>(k)],
                                      k,
                                      tcrit,
                                      options.power_z,
                                      series,
                                      slope_words,
                                      bias_change_p));
  }
  const ClusteredFit base_fit = ls.Fit(base);
  r.summary.channel = series.name;
  r.summary.unit = series.unit;
  r.summary.held_out_rms_baseline = HeldOutRms(base_fit, sel.fit, false, 1.0);
  r.summary.held_out_rms_final = HeldOutRms(base_fit, sel.fit, true, 1.0);
  std::vector<double> white;
  for (const Cell& c : p.cells)
    white.push_back(std::sqrt(c.var[static_cast<size_t>(out)] / c.rows));
  r.summary.white_noise_rms = common::Median(white);
  if (has_slope) {
    r.summary.bias_slope_per_c = slope;
    r.summary.bias_slope_se_per_c = slope_se;
  }
  if (auto excess = HeldOutExcess(r.summary, sel.fit, p.labels, 1.0))
    r.unexplained.push_back(std::move(*excess));
  for (int c : base)
    r.summary.baseline_terms.push_back(c <= kMaxBiasDegree ? fmt::format("s^{}", c) : "reference");
  const std::vector<double> rb = Residuals(cols, p, out, bias, base_fit, base);
  const std::vector<double> rf = Residuals(cols, p, out, bias, sel.fit, sel.selected);
  for (size_t i = 0; i < p.cells.size() && static_cast<int>(i) < kPlotCells; ++i) {
    r.summary.plot_t_s.push_back(p.cells[i].t_s);
    r.summary.plot_temp_c.push_back(p.cells[i].temp_c);
    r.summary.plot_residual_baseline.push_back(rb[i]);
    r.summary.plot_residual_final.push_back(rf[i]);
  }
  return r;
}

// Periodic lines in the rows of each output (row_spectrum.h).
void LocatePeriodic(const ChannelRecording& rec,
                    const Prepared& p,
                    double alpha,
                    UnitDiagnosis* out) {
  std::vector<double> rows;
  for (const auto& [a, b] : p.segment_rows) rows.push_back(static_cast<double>(b - a));
  const double median_rows = common::Median(rows);
  int window = 64;
  while (window * 2 <= std::min(512.0, median_rows)) window *= 2;
  RowSpectra spectra(static_cast<int>(rec.outputs.size()), MedianInterval(rec.t_s), window);
  for (size_t s = 0; s < p.segment_rows.size(); ++s) {
    const size_t a = p.segment_rows[s].first;
    spectra.AddSegment(
        static_cast<int>(s),
        p.segment_rows[s].second - a,
        [&](size_t i) { return rec.t_s[a + i]; },
        [&](size_t i, int c) { return rec.outputs[static_cast<size_t>(c)].values[a + i]; });
  }
  for (size_t c = 0; c < rec.outputs.size(); ++c) {
    const ChannelSeries& o = rec.outputs[c];
    for (const PeriodicLine& line : FindPeriodicLines(spectra, static_cast<int>(c), alpha)) {
      const std::string what = fmt::format(
          "periodic {:.3g} Hz, amplitude {:.3g} {}, {:.1f} times the noise floor at that "
          "frequency",
          line.frequency_hz,
          line.amplitude,
          o.unit,
          line.floor_ratio);
      if (line.amplitude < 0.5 * o.resolution) {
        out->notes.push_back(fmt::format("{}: {}: below half the output's resolution ({:.3g} {})",
                                         o.name,
                                         what,
                                         o.resolution,
                                         o.unit));
        continue;
      }
      out->unexplained.push_back({o.name,
                                  fmt::format("rows of {} of {} segments with {}-row windows",
                                              line.segments.size(),
                                              line.segments_with_windows,
                                              window),
                                  what + "; no candidate term explains it",
                                  line.amplitude,
                                  o.unit});
    }
  }
}

}  // namespace

UnitDiagnosis DiagnoseChannels(const ChannelRecording& rec, const DiagnosisOptions& options) {
  const Prepared p = Prepare(rec);
  UnitDiagnosis out;
  out.serial = rec.unit;
  out.rows = static_cast<int>(rec.t_s.size());
  out.segments = static_cast<int>(p.segment_rows.size());
  out.cells = static_cast<int>(p.cells.size());
  out.temp_span_c = p.span_c;
  out.tests = static_cast<int>(rec.outputs.size()) * kCandidates;
  out.test_alpha = options.family_alpha / out.tests;
  out.notes = rec.notes;
  for (size_t o = 0; o < rec.outputs.size(); ++o) {
    OutputResult r =
        DiagnoseOutput(rec, p, static_cast<int>(o), out.test_alpha, options, &out.notes);
    for (Finding& f : r.findings) out.findings.push_back(std::move(f));
    for (Unexplained& u : r.unexplained) out.unexplained.push_back(std::move(u));
    for (DetectionLimit& l : r.limits) out.detection_limits.push_back(std::move(l));
    out.channels.push_back(std::move(r.summary));
  }
  LocatePeriodic(rec, p, options.family_alpha / static_cast<double>(rec.outputs.size()), &out);
  return out;
}

}  // namespace adahrs::diagnosis
