#include "diagnosis/ads_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "calib/ads_calibration/bridge_history.h"
#include "calib/ads_calibration/hysteresis_span_fit.h"
#include "diagnosis/clustered_least_squares.h"
#include "diagnosis/plausible_range.h"
#include "diagnosis/term_selection.h"

namespace adahrs::diagnosis {
namespace {

constexpr double kNewSweepTempC = 2.0;  // a chamber change this large starts a sweep
constexpr int kMinSweeps = 4;
constexpr int kMinTemperatures =
    4;  // two interior ones to choose the degree in the voltage code by
constexpr std::array<int, 2> kPressureDegrees = {2, 3};
constexpr int kMinVoltageDegree = 1;
constexpr int kMaxVoltageDegree = 7;
constexpr int kStartVoltageDegree = 3;
constexpr int kPointsPerRun = 5;  // one temperature: consecutive points held out together

enum class Effect { kPressureHysteresis, kThermalHysteresis, kNonlinearity };
constexpr std::array<Effect, 3> kEffects = {
    Effect::kPressureHysteresis, Effect::kThermalHysteresis, Effect::kNonlinearity};

std::string EffectName(Effect e) {
  switch (e) {
    case Effect::kPressureHysteresis:
      return "pressure_hysteresis";
    case Effect::kThermalHysteresis:
      return "thermal_hysteresis";
    case Effect::kNonlinearity:
      return "bridge_nonlinearity";
  }
  return "?";
}

// One bridge's points: output code, applied pressure, voltage code, hysteresis states.
struct Bridge {
  std::string channel;
  std::vector<double> code, p_pa, v_cnt, s_p, s_t, chamber_c;
  std::vector<int> sweep;
  std::vector<int> block;  ///< chamber temperature visited, coldest 0
  int blocks = 0;
  double p_mid = 0, p_half = 1, v_mid = 0, v_half = 1, v_mean = 1;
  double u(size_t i) const { return (p_pa[i] - p_mid) / p_half; }
  double v(size_t i) const { return (v_cnt[i] - v_mid) / v_half; }
  // A bridge's output is ratiometric: a resistance change, whatever moved it, reads in
  // proportion to the excitation across the bridge, whose code is the thermometer V_B. A
  // hysteresis state's contribution scales with it (with R_B's tempco, ~0.26 %/degC).
  double excitation(size_t i) const { return v_cnt[i] / v_mean; }
};

void Scale(const std::vector<double>& x, double* mid, double* half) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  *mid = 0.5 * (*lo + *hi);
  *half = std::max(0.5 * (*hi - *lo), 1e-9);
}

// Sweep index per point, and a label per sweep.
std::vector<int> Sweeps(const std::vector<calib::AdsCalibrationPoint>& pts,
                        std::vector<std::string>* labels) {
  std::vector<int> sweep(pts.size(), 0);
  int moving = -1, sense = 0;
  auto label = [&](size_t first) {
    labels->push_back(fmt::format("sweep {} from step {} at {:.0f} degC",
                                  labels->size() + 1,
                                  pts[first].step,
                                  pts[first].chamber_c));
  };
  label(0);
  for (size_t i = 1; i < pts.size(); ++i) {
    const double dps = pts[i].ps_ref_pa - pts[i - 1].ps_ref_pa,
                 dqc = pts[i].qc_ref_pa - pts[i - 1].qc_ref_pa;
    const int m = std::abs(dps) >= std::abs(dqc) ? 0 : 1;
    const int s = (m == 0 ? dps : dqc) >= 0.0 ? 1 : -1;
    const bool hotter = std::abs(pts[i].chamber_c - pts[i - 1].chamber_c) > kNewSweepTempC;
    if (hotter || (moving >= 0 && (m != moving || s != sense))) {
      label(i);
      moving = hotter ? -1 : m;
      sense = s;
    } else if (moving < 0) {
      moving = m;
      sense = s;
    }
    sweep[i] = static_cast<int>(labels->size()) - 1;
  }
  return sweep;
}

// At one temperature a few sweeps hold every point: each sweep is cut into runs of at most
// kPointsPerRun consecutive points, the clusters the jackknife and the held-out error leave out.
std::vector<int> RunsOfSweeps(const std::vector<calib::AdsCalibrationPoint>& pts,
                              const std::vector<int>& sweep,
                              const std::vector<std::string>& sweep_labels,
                              std::vector<std::string>* labels) {
  std::vector<int> run(pts.size(), 0);
  labels->clear();
  int in_run = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (i == 0 || sweep[i] != sweep[i - 1] || in_run == kPointsPerRun) {
      labels->push_back(fmt::format(
          "{}, points from step {}", sweep_labels[static_cast<size_t>(sweep[i])], pts[i].step));
      in_run = 0;
    }
    ++in_run;
    run[i] = static_cast<int>(labels->size()) - 1;
  }
  return run;
}

Bridge MakeBridge(bool pitot,
                  const std::vector<calib::AdsCalibrationPoint>& pts,
                  const std::vector<calib::PointHistory>& hist,
                  const std::vector<int>& sweep) {
  Bridge b;
  b.channel = pitot ? "pt" : "ps";
  b.sweep = sweep;
  for (size_t i = 0; i < pts.size(); ++i) {
    const calib::BridgeStates& st = pitot ? hist[i].pitot_bridge : hist[i].static_bridge;
    b.code.push_back(pitot ? pts[i].pt_cnt : pts[i].ps_cnt);
    b.p_pa.push_back(pitot ? pts[i].qc_ref_pa : pts[i].ps_ref_pa);
    b.v_cnt.push_back(pitot ? pts[i].pt_temp_cnt : pts[i].ps_temp_cnt);
    b.s_p.push_back(st.s_pressure);
    b.s_t.push_back(st.s_thermal);
    b.chamber_c.push_back(pts[i].chamber_c);
  }
  Scale(b.p_pa, &b.p_mid, &b.p_half);
  Scale(b.v_cnt, &b.v_mid, &b.v_half);
  b.v_mean =
      std::accumulate(b.v_cnt.begin(), b.v_cnt.end(), 0.0) / static_cast<double>(b.v_cnt.size());
  std::vector<double> temps = b.chamber_c;
  std::sort(temps.begin(), temps.end());
  std::vector<double> levels;
  for (double t : temps) {
    if (levels.empty() || t - levels.back() > kNewSweepTempC) levels.push_back(t);
  }
  for (double t : b.chamber_c) {
    int k = 0;
    while (k + 1 < static_cast<int>(levels.size()) &&
           t - levels[static_cast<size_t>(k) + 1] >= -kNewSweepTempC)
      ++k;
    b.block.push_back(k);
  }
  b.blocks = static_cast<int>(levels.size());
  return b;
}

// The bridge's hysteresis states under its own spans (the other bridge's are irrelevant here).
void SetStates(Bridge* b,
               bool pitot,
               const std::vector<calib::AdsCalibrationPoint>& pts,
               double pressure_span_pa,
               double thermal_span_c) {
  calib::HysteresisSpans spans = calib::HysteresisSpans::Nominal();
  (pitot ? spans.impact_pressure_pa : spans.static_pressure_pa) = pressure_span_pa;
  (pitot ? spans.pitot_temperature_c : spans.static_temperature_c) = thermal_span_c;
  const std::vector<calib::PointHistory> hist = calib::BridgeHistoryOf(pts, spans);
  for (size_t i = 0; i < pts.size(); ++i) {
    const calib::BridgeStates& st = pitot ? hist[i].pitot_bridge : hist[i].static_bridge;
    b->s_p[i] = st.s_pressure;
    b->s_t[i] = st.s_thermal;
  }
}

// Column layout: the baseline terms u^a v^c, c <= dv[a], for a <= dp, then each candidate's
// columns.
struct Layout {
  bool one_temperature = false;  ///< no temperature terms: thermal hysteresis is not a candidate
  int dp = 0;
  std::vector<int> dv;                     ///< per power of u
  std::vector<std::pair<int, int>> terms;  ///< (a, c) of each baseline column
  int baseline = 0;
  std::array<std::vector<int>, 3> candidate;
  int columns = 0;
};

Layout MakeLayout(const std::vector<int>& dv, bool one_temperature) {
  Layout l;
  l.one_temperature = one_temperature;
  l.dp = static_cast<int>(dv.size()) - 1;
  l.dv = dv;
  for (int a = 0; a <= l.dp; ++a) {
    for (int c = 0; c <= dv[static_cast<size_t>(a)]; ++c) l.terms.emplace_back(a, c);
  }
  l.baseline = static_cast<int>(l.terms.size());
  int next = l.baseline;
  l.candidate[0] = {next++};
  if (!one_temperature) l.candidate[1] = {next++};
  l.candidate[2] = {next++};
  if (!one_temperature) l.candidate[2].push_back(next++);
  l.columns = next;
  return l;
}

Eigen::VectorXd Row(const Layout& l, const Bridge& b, size_t i) {
  Eigen::VectorXd x(l.columns);
  const double u = b.u(i), v = b.v(i);
  for (size_t k = 0; k < l.terms.size(); ++k) {
    x[static_cast<int>(k)] = std::pow(u, l.terms[k].first) * std::pow(v, l.terms[k].second);
  }
  x[l.candidate[0][0]] = b.s_p[i] * b.excitation(i);
  if (!l.candidate[1].empty()) x[l.candidate[1][0]] = b.s_t[i] * b.excitation(i);
  x[l.candidate[2][0]] = std::pow(u, l.dp + 1);
  if (l.candidate[2].size() > 1) x[l.candidate[2][1]] = std::pow(u, l.dp + 1) * v;
  return x;
}

ClusteredLeastSquares Accumulate(const Layout& l, const Bridge& b, int sweeps, double y_mid) {
  ClusteredLeastSquares ls(l.columns, sweeps);
  for (size_t i = 0; i < b.code.size(); ++i)
    ls.Add(b.sweep[i], Row(l, b, i), b.code[i] - y_mid, 1.0);
  return ls;
}

std::vector<int> Range(int n) {
  std::vector<int> v(static_cast<size_t>(n));
  std::iota(v.begin(), v.end(), 0);
  return v;
}

// Mean dcode/dP over the points under the baseline coefficients of `fit` (the first columns).
double Sensitivity(const Layout& l, const Bridge& b, const ClusteredFit& fit) {
  double sum = 0.0;
  for (size_t i = 0; i < b.code.size(); ++i) {
    const double u = b.u(i), v = b.v(i);
    for (size_t k = 0; k < l.terms.size(); ++k) {
      const auto [a, c] = l.terms[k];
      if (a > 0) sum += fit.theta[static_cast<int>(k)] * a * std::pow(u, a - 1) * std::pow(v, c);
    }
  }
  return sum / static_cast<double>(b.code.size()) / b.p_half;
}

struct BaselineChoice {
  Layout layout;
  ClusteredLeastSquares ls{1, 1};
  ClusteredFit fit;
  double held_out_ss = 0.0;
};

// The baseline's error at each interior temperature under the fit made without it (the coldest
// and hottest are extrapolation): a degree in the voltage code is chosen by temperatures it did
// not see, as the calibration chooses it, never by sweeps that share a temperature. NaN when a
// leave-out fit is singular.
double HeldOutTemperatureSs(const Layout& l, const Bridge& b, double y_mid) {
  const std::vector<int> base = Range(l.baseline);
  ClusteredLeastSquares by_temp(l.columns, b.blocks);
  for (size_t i = 0; i < b.code.size(); ++i)
    by_temp.Add(b.block[i], Row(l, b, i), b.code[i] - y_mid, 1.0);
  if (!by_temp.FullRank(base)) return std::nan("");
  const ClusteredFit held = by_temp.Fit(base);
  if (!held.ok) return std::nan("");
  double ss = 0.0;
  for (int k = 1; k + 1 < b.blocks; ++k) ss += held.held_out_ss[static_cast<size_t>(k)];
  return ss;
}

// Fits the baseline of degrees `dv` (per power of u); false when it cannot be fitted or held out.
// Scored by held-out temperatures; at one temperature (no voltage terms) by held-out sweeps.
bool TryBaseline(
    const Bridge& b, int sweeps, double y_mid, const std::vector<int>& dv, BaselineChoice* out) {
  const Layout l = MakeLayout(dv, b.blocks == 1);
  ClusteredLeastSquares ls = Accumulate(l, b, sweeps, y_mid);
  ClusteredFit fit = ls.Fit(Range(l.baseline));
  if (!fit.ok || !fit.jackknife_ok) return false;
  double ss = 0.0;
  if (l.one_temperature) {
    for (double s : fit.held_out_ss) ss += s;
  } else {
    ss = HeldOutTemperatureSs(l, b, y_mid);
  }
  if (!std::isfinite(ss)) return false;
  *out = {l, std::move(ls), std::move(fit), ss};
  return true;
}

// The degrees whose baseline has the smallest leave-one-sweep-out error: per degree in pressure,
// the degree in the voltage code of each power of u by coordinate descent from kStartVoltageDegree.
BaselineChoice ChooseBaseline(const Bridge& b, int sweeps, double y_mid) {
  BaselineChoice best;
  bool found = false;
  for (int dp : kPressureDegrees) {
    std::vector<int> dv(static_cast<size_t>(dp) + 1, b.blocks == 1 ? 0 : kStartVoltageDegree);
    BaselineChoice current;
    if (!TryBaseline(b, sweeps, y_mid, dv, &current)) continue;
    for (bool improved = b.blocks > 1; improved;) {
      improved = false;
      for (size_t a = 0; a < dv.size(); ++a) {
        for (int d = kMinVoltageDegree; d <= kMaxVoltageDegree; ++d) {
          std::vector<int> trial = dv;
          trial[a] = d;
          BaselineChoice c;
          if (trial == dv || !TryBaseline(b, sweeps, y_mid, trial, &c) ||
              c.held_out_ss >= current.held_out_ss)
            continue;
          current = std::move(c);
          dv = trial;
          improved = true;
        }
      }
    }
    if (!found || current.held_out_ss < best.held_out_ss) best = std::move(current);
    found = true;
  }
  if (!found)
    throw std::runtime_error(
        fmt::format("{}: no baseline polynomial can be fitted to these points", b.channel));
  return best;
}

std::vector<FindingComponent> Components(Effect e,
                                         const Eigen::VectorXd& theta,
                                         const Eigen::VectorXd& se,
                                         double sens,
                                         const Layout& l,
                                         const Bridge& b) {
  if (e != Effect::kNonlinearity)
    return {{"half_loop", theta[0] / sens, se[0] / std::abs(sens), "Pa"}};
  double u_max = 0.0;
  for (size_t i = 0; i < b.p_pa.size(); ++i) u_max = std::max(u_max, std::abs(b.u(i)));
  const double k = std::pow(u_max, l.dp + 1) / sens;
  std::vector<FindingComponent> out = {
      {"at_largest_travel", theta[0] * k, se[0] * std::abs(k), "Pa"}};
  // v spans [-1, 1]: the change across the temperature span is twice the v coefficient.
  if (theta.size() > 1)
    out.push_back(
        {"change_across_temperature_span", 2.0 * theta[1] * k, 2.0 * se[1] * std::abs(k), "Pa"});
  return out;
}

std::string Words(Effect e,
                  const std::vector<FindingComponent>& c,
                  const Bridge& b,
                  const Layout& l) {
  const std::string name = b.channel == "ps" ? "the static bridge (ps)" : "the pitot bridge (pt)";
  auto pm = [](const FindingComponent& x) {
    return fmt::format("{:.3g} ± {:.2g} {}", x.magnitude, x.standard_error, x.unit);
  };
  switch (e) {
    case Effect::kPressureHysteresis:
      return fmt::format(
          "{} reads {} higher after a pressure fall than after a rise (half the loop): pressure "
          "hysteresis is missing from the model",
          name,
          pm(c[0]));
    case Effect::kThermalHysteresis:
      return fmt::format(
          "{} reads {} higher after cooling than after heating (half the loop): thermal hysteresis "
          "is missing from the model",
          name,
          pm(c[0]));
    case Effect::kNonlinearity:
      return fmt::format(
          "{} departs from a degree-{} polynomial in pressure by {} at its largest travel{}: "
          "bridge nonlinearity beyond the modelled order is missing from the model",
          name,
          l.dp,
          pm(c[0]),
          c.size() > 1 ? fmt::format(" ({} across the temperature span)", pm(c[1])) : "");
  }
  return "";
}

std::vector<double> Residuals(const Layout& l,
                              const Bridge& b,
                              const ClusteredFit& fit,
                              const std::vector<int>& subset,
                              double y_mid) {
  std::vector<double> r;
  for (size_t i = 0; i < b.code.size(); ++i) {
    const Eigen::VectorXd x = Row(l, b, i);
    double pred = 0.0;
    for (size_t k = 0; k < subset.size(); ++k)
      pred += x[subset[k]] * fit.theta[static_cast<int>(k)];
    r.push_back(b.code[i] - y_mid - pred);
  }
  return r;
}

// Sweeps where the term's contribution |x theta| is largest on average.
std::vector<std::string> Evidence(const Layout& l,
                                  const Bridge& b,
                                  const std::vector<int>& columns,
                                  const Eigen::VectorXd& theta,
                                  const std::vector<std::string>& labels) {
  std::vector<double> sum(labels.size(), 0.0), n(labels.size(), 0.0);
  for (size_t i = 0; i < b.code.size(); ++i) {
    const Eigen::VectorXd x = Row(l, b, i);
    double v = 0.0;
    for (size_t k = 0; k < columns.size(); ++k) v += x[columns[k]] * theta[static_cast<int>(k)];
    sum[static_cast<size_t>(b.sweep[i])] += std::abs(v);
    n[static_cast<size_t>(b.sweep[i])] += 1.0;
  }
  std::vector<int> order = Range(static_cast<int>(labels.size()));
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return sum[x] / std::max(1.0, n[x]) > sum[y] / std::max(1.0, n[y]);
  });
  std::vector<std::string> out;
  for (size_t i = 0; i < order.size() && i < 3; ++i)
    out.push_back(labels[static_cast<size_t>(order[i])]);
  return out;
}

struct BridgeResult {
  std::vector<Finding> findings;
  std::vector<DetectionLimit> limits;
  ChannelFitSummary summary;
};

// Forward selection over the candidates; returns the chosen effects in order.
std::vector<Effect> Select(const BaselineChoice& bc,
                           double alpha,
                           int max_findings,
                           std::vector<int>* selected,
                           ClusteredFit* selected_fit) {
  const std::vector<std::vector<int>> candidates(bc.layout.candidate.begin(),
                                                 bc.layout.candidate.end());
  // A candidate without columns is not testable on these points (one temperature).
  const auto testable = [&](int k, const std::vector<int>&) {
    return !candidates[static_cast<size_t>(k)].empty();
  };
  TermSelection sel = SelectTerms(
      bc.ls, Range(bc.layout.baseline), bc.fit, candidates, alpha, max_findings, testable);
  *selected = std::move(sel.selected);
  *selected_fit = std::move(sel.fit);
  std::vector<Effect> chosen;
  for (int k : sel.chosen) chosen.push_back(kEffects[static_cast<size_t>(k)]);
  return chosen;
}

Finding MakeFinding(Effect e,
                    const BaselineChoice& bc,
                    const Bridge& b,
                    const std::vector<int>& selected,
                    const ClusteredFit& selected_fit,
                    double sens,
                    const std::vector<std::string>& labels,
                    const std::optional<calib::SpanFit>& spans) {
  const std::vector<int>& cols = bc.layout.candidate[static_cast<int>(e)];
  const std::vector<int> without = WithoutColumns(selected, cols);
  const ClusteredFit fit_without = bc.ls.Fit(without);
  Eigen::VectorXd theta, se;
  ColumnEstimates(selected_fit, selected, cols, &theta, &se);
  Finding f;
  f.effect = EffectName(e);
  f.channel = b.channel;
  f.components = Components(e, theta, se, sens, bc.layout, b);
  if (spans && e == Effect::kPressureHysteresis) {
    f.components.push_back({"span", spans->pressure_span, spans->pressure_span_se, "Pa"});
  }
  if (spans && e == Effect::kThermalHysteresis) {
    f.components.push_back({"span", spans->thermal_span_c, spans->thermal_span_c_se, "degC"});
  }
  f.held_out_rms_before = HeldOutRms(fit_without, selected_fit, false, 1.0 / std::abs(sens));
  f.held_out_rms_after = HeldOutRms(fit_without, selected_fit, true, 1.0 / std::abs(sens));
  f.rms_unit = "Pa";
  f.evidence = Evidence(bc.layout, b, cols, theta, labels);
  f.words = Words(e, f.components, b, bc.layout);
  f.wald_p_value = TestTerm(bc.ls, without, fit_without, cols).p_value;
  return f;
}

// The spans of the bridge's chosen hysteresis effects that let the selected model explain the
// points best (hysteresis_span_fit.h); the bridge's states and the fits are then redone with them.
std::optional<calib::SpanFit> RefitSpans(Bridge* b,
                                         bool pitot,
                                         const std::vector<calib::AdsCalibrationPoint>& pts,
                                         const std::vector<Effect>& chosen,
                                         const std::vector<int>& selected,
                                         int sweeps,
                                         double y_mid,
                                         BaselineChoice* bc,
                                         ClusteredFit* selected_fit,
                                         std::vector<std::string>* notes) {
  auto has = [&](Effect e) { return std::find(chosen.begin(), chosen.end(), e) != chosen.end(); };
  if (!has(Effect::kPressureHysteresis) && !has(Effect::kThermalHysteresis)) return std::nullopt;
  const calib::HysteresisSpans nominal = calib::HysteresisSpans::Nominal();
  const double p0 = pitot ? nominal.impact_pressure_pa : nominal.static_pressure_pa;
  const double t0 = pitot ? nominal.pitot_temperature_c : nominal.static_temperature_c;
  Bridge trial = *b;
  auto cost = [&](double p_span, double t_span) {
    SetStates(&trial, pitot, pts, p_span, t_span);
    return Accumulate(bc->layout, trial, sweeps, y_mid).Fit(selected).rss;
  };
  const int dof = static_cast<int>(pts.size()) - static_cast<int>(selected.size());
  const calib::SpanFit spans =
      calib::FitHysteresisSpans(cost, p0, t0, std::max(1, dof), 2.0 * b->p_half);
  const double p = has(Effect::kPressureHysteresis) ? spans.pressure_span : p0;
  const double t = has(Effect::kThermalHysteresis) ? spans.thermal_span_c : t0;
  SetStates(b, pitot, pts, p, t);
  bc->ls = Accumulate(bc->layout, *b, sweeps, y_mid);
  bc->fit = bc->ls.Fit(Range(bc->layout.baseline));
  *selected_fit = bc->ls.Fit(selected);
  notes->push_back(fmt::format(
      "{}: hysteresis spans fitted to the points: pressure {:.0f} Pa, thermal {:.1f} degC{}",
      b->channel,
      p,
      t,
      spans.at_search_edge ? " (on the search box's edge)" : ""));
  return spans;
}

// The spans the bridge's states were set with after RefitSpans: the fitted one of each chosen
// hysteresis effect, the nominal one of the other.
std::pair<double, double> UsedSpans(bool pitot,
                                    const calib::SpanFit& spans,
                                    const std::vector<Effect>& chosen) {
  auto has = [&](Effect e) { return std::find(chosen.begin(), chosen.end(), e) != chosen.end(); };
  const calib::HysteresisSpans nominal = calib::HysteresisSpans::Nominal();
  return {has(Effect::kPressureHysteresis)
              ? spans.pressure_span
              : (pitot ? nominal.impact_pressure_pa : nominal.static_pressure_pa),
          has(Effect::kThermalHysteresis)
              ? spans.thermal_span_c
              : (pitot ? nominal.pitot_temperature_c : nominal.static_temperature_c)};
}

// A hysteresis finding's half loop is fitted at its span; the span's own uncertainty moves it too.
// The half loop refitted with the span at ± one standard error (the other span fixed): half the
// change is added in quadrature to the half loop's standard error, which otherwise holds the span
// exact (a loop that never saturates, the pitot's, trades loop height for span).
void AddSpanUncertainty(Finding* f,
                        Effect e,
                        const Bridge& b,
                        bool pitot,
                        const std::vector<calib::AdsCalibrationPoint>& pts,
                        const std::pair<double, double>& used,
                        const calib::SpanFit& spans,
                        const BaselineChoice& bc,
                        const std::vector<int>& selected,
                        int sweeps,
                        double y_mid,
                        double sens) {
  const bool pressure = e == Effect::kPressureHysteresis;
  const double se_span = pressure ? spans.pressure_span_se : spans.thermal_span_c_se;
  const double span = pressure ? used.first : used.second;
  if (!std::isfinite(se_span) || !(se_span > 0.0) || se_span >= span) return;
  const std::vector<int>& cols = bc.layout.candidate[static_cast<int>(e)];
  double half[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const double moved = span + (k == 0 ? -se_span : se_span);
    Bridge trial = b;
    SetStates(&trial, pitot, pts, pressure ? moved : used.first, pressure ? used.second : moved);
    const ClusteredFit fit = Accumulate(bc.layout, trial, sweeps, y_mid).Fit(selected);
    if (!fit.ok) return;
    Eigen::VectorXd theta, se;
    ColumnEstimates(fit, selected, cols, &theta, &se);
    half[k] = theta[0] / sens;
  }
  FindingComponent& h = f->components[0];
  h.standard_error = std::hypot(h.standard_error, 0.5 * (half[1] - half[0]));
  f->words = Words(e, f->components, b, bc.layout);
}

BridgeResult DiagnoseBridge(Bridge b,
                            bool pitot,
                            const std::vector<calib::AdsCalibrationPoint>& pts,
                            const std::vector<std::string>& labels,
                            double alpha,
                            const DiagnosisOptions& options,
                            std::vector<std::string>* notes) {
  const int sweeps = static_cast<int>(labels.size());
  const double y_mid =
      std::accumulate(b.code.begin(), b.code.end(), 0.0) / static_cast<double>(b.code.size());
  BaselineChoice bc = ChooseBaseline(b, sweeps, y_mid);
  std::vector<int> selected;
  ClusteredFit selected_fit;
  const std::vector<Effect> first =
      Select(bc, alpha, options.max_findings_per_channel, &selected, &selected_fit);
  const std::optional<calib::SpanFit> spans =
      RefitSpans(&b, pitot, pts, first, selected, sweeps, y_mid, &bc, &selected_fit, notes);
  // With the spans fitted, the selection is made again: a term that stood in for the nominal
  // spans' error is no longer needed.
  const std::vector<Effect> chosen =
      spans ? Select(bc, alpha, options.max_findings_per_channel, &selected, &selected_fit) : first;
  const double sens = Sensitivity(bc.layout, b, selected_fit);
  const double pa = 1.0 / std::abs(sens);
  notes->push_back(fmt::format(
      "{}: baseline of degree {} in pressure, of degrees {} in the bridge-voltage code "
      "per power of pressure (least leave-one-sweep-out error); sensitivity {:.4g} codes/Pa",
      b.channel,
      bc.layout.dp,
      fmt::join(bc.layout.dv, ", "),
      sens));
  BridgeResult out;
  for (Effect e : chosen) {
    const bool refit = std::find(first.begin(), first.end(), e) != first.end();
    out.findings.push_back(
        MakeFinding(e, bc, b, selected, selected_fit, sens, labels, refit ? spans : std::nullopt));
    if (refit && spans && e != Effect::kNonlinearity) {
      AddSpanUncertainty(&out.findings.back(),
                         e,
                         b,
                         pitot,
                         pts,
                         UsedSpans(pitot, *spans, first),
                         *spans,
                         bc,
                         selected,
                         sweeps,
                         y_mid,
                         sens);
    }
  }
  const double tcrit = TCritical(alpha, selected_fit.clusters);
  for (int e = 0; e < 3; ++e) {
    DetectionLimit lim;
    lim.effect = EffectName(kEffects[e]);
    lim.channel = b.channel;
    Eigen::VectorXd se;
    if (bc.layout.candidate[e].empty()) {
      lim.note = "not testable here: the points visit one chamber temperature";
    } else if (LimitStandardErrors(bc.ls, selected, bc.layout.candidate[e], &se, &lim.note)) {
      lim.limits = Components(kEffects[e], se * (tcrit + options.power_z), se, sens, bc.layout, b);
      for (FindingComponent& c : lim.limits) c.magnitude = std::abs(c.magnitude);
      lim.note = NotTestableBridgeReason(lim.limits, 2.0 * b.p_half);
      if (!lim.note.empty()) lim.limits.clear();
    }
    out.limits.push_back(std::move(lim));
  }
  const std::vector<int> base = Range(bc.layout.baseline);
  out.summary.channel = b.channel;
  out.summary.unit = "Pa";
  out.summary.residuals = ChannelFitSummary::Residuals::kPerCalibrationPoint;
  out.summary.held_out_rms_baseline = HeldOutRms(bc.fit, selected_fit, false, pa);
  out.summary.held_out_rms_final = HeldOutRms(bc.fit, selected_fit, true, pa);
  for (const auto& [a, c] : bc.layout.terms)
    out.summary.baseline_terms.push_back(fmt::format("u^{} v^{}", a, c));
  const std::vector<double> r_base = Residuals(bc.layout, b, bc.fit, base, y_mid);
  const std::vector<double> r_final = Residuals(bc.layout, b, selected_fit, selected, y_mid);
  for (size_t i = 0; i < b.code.size(); ++i) {
    out.summary.plot_t_s.push_back(pts[i].step);
    out.summary.plot_temp_c.push_back(b.chamber_c[i]);
    out.summary.plot_residual_baseline.push_back(r_base[i] / sens);
    out.summary.plot_residual_final.push_back(r_final[i] / sens);
  }
  return out;
}

}  // namespace

UnitDiagnosis DiagnoseAds(const std::string& serial,
                          const std::vector<calib::AdsCalibrationPoint>& points,
                          const DiagnosisOptions& options) {
  std::vector<std::string> labels;
  if (points.empty())
    throw std::runtime_error(fmt::format("{}: no calibration points to diagnose", serial));
  std::vector<int> sweep = Sweeps(points, &labels);
  const std::vector<calib::PointHistory> hist = calib::BridgeHistoryOf(points);
  const int temperatures = MakeBridge(false, points, hist, sweep).blocks;
  if (temperatures == 1) {
    const std::vector<std::string> sweep_labels = std::move(labels);
    sweep = RunsOfSweeps(points, sweep, sweep_labels, &labels);
  }
  if (static_cast<int>(labels.size()) < kMinSweeps) {
    throw std::runtime_error(
        fmt::format("{}: {} sweep(s) of calibration points; diagnosis needs at least {} to hold "
                    "one out",
                    serial,
                    labels.size(),
                    kMinSweeps));
  }
  if (temperatures > 1 && temperatures < kMinTemperatures) {
    throw std::runtime_error(
        fmt::format("{}: the points visit {} chamber temperatures; the baseline's degree in "
                    "temperature is chosen by held-out interior temperatures and needs at least "
                    "{} (or one, where temperature is not modelled)",
                    serial,
                    temperatures,
                    kMinTemperatures));
  }
  UnitDiagnosis out;
  out.serial = serial;
  out.segments = static_cast<int>(labels.size());
  out.cells = static_cast<int>(points.size());
  double lo = 1e9, hi = -1e9;
  for (const calib::AdsCalibrationPoint& p : points) {
    out.rows += p.rows;
    lo = std::min(lo, p.chamber_c);
    hi = std::max(hi, p.chamber_c);
  }
  out.temp_span_c = hi - lo;
  // At one temperature thermal hysteresis has no column on either bridge.
  out.tests = 2 * static_cast<int>(kEffects.size() - (temperatures == 1 ? 1 : 0));
  out.test_alpha = options.family_alpha / out.tests;
  out.notes.push_back(
      "points are step means after a soak: die lag and self-heating leave no trace in them and are "
      "not tested");
  if (temperatures == 1)
    out.notes.push_back(
        "one chamber temperature: the baseline is a polynomial in pressure alone, its degree "
        "chosen by held-out runs of at most 5 consecutive points of a sweep; thermal hysteresis "
        "and any change with temperature are not testable");
  for (bool pitot : {false, true}) {
    BridgeResult r = DiagnoseBridge(MakeBridge(pitot, points, hist, sweep),
                                    pitot,
                                    points,
                                    labels,
                                    out.test_alpha,
                                    options,
                                    &out.notes);
    for (Finding& f : r.findings) out.findings.push_back(std::move(f));
    for (DetectionLimit& l : r.limits) out.detection_limits.push_back(std::move(l));
    out.channels.push_back(std::move(r.summary));
  }
  return out;
}

}  // namespace adahrs::diagnosis
