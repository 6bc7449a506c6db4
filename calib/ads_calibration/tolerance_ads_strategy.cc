#include "calib/ads_calibration/tolerance_ads_strategy.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "calib/acceptance/ads_tolerance.h"
#include "calib/ads_calibration/bridge_history.h"
#include "calib/ads_calibration/bridge_linearisation_fit.h"
#include "calib/ads_calibration/hysteresis_span_fit.h"
#include "calib/constants/constants_file.h"
#include "calib/solvers/polynomial_fit.h"
#include "firmware_model/air_data_law.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

struct MinimaxSurface {
  SurfaceEstimate estimate;
  double first_worst_ratio = 0.0;  ///< of the 1/tol^2 fit
  double worst_ratio = 0.0;        ///< of the kept iterate
};

// The fit's value at a sample: the surface, plus its branch when the fit has history terms (the
// gains' temperature slopes are zero unless the fit had them).
double Predicted(const SurfaceEstimate& e, const SurfaceSample& s) {
  double z = firmware_model::EvaluateSurfaceFit(e.surface, s.x_code, s.y_code);
  if (e.history) {
    const HysteresisEstimate& h = *e.history;
    const double dt_c = s.chamber_c - kHysteresisReferenceC;
    z += (h.pressure + h.pressure_per_c * dt_c) * s.s_pressure +
         (h.thermal + h.thermal_per_c * dt_c) * s.s_thermal;
  }
  return z;
}

double WorstRatio(const SurfaceEstimate& e,
                  const std::vector<SurfaceSample>& samples,
                  const std::vector<double>& tolerance,
                  std::vector<double>& ratio) {
  double worst = 0.0;
  for (size_t i = 0; i < samples.size(); ++i) {
    ratio[i] = std::abs(Predicted(e, samples[i]) - samples[i].z) / tolerance[i];
    worst = std::max(worst, ratio[i]);
  }
  return worst;
}

std::vector<double> Tolerances(const std::vector<SurfaceSample>& samples,
                               const std::function<double(double)>& tolerance_of) {
  std::vector<double> tolerance(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) tolerance[i] = tolerance_of(samples[i].z);
  return tolerance;
}

// Each sample weighted 1/tol^2 (the tolerance-weighted mean-square fit).
void WeighByTolerance(std::vector<SurfaceSample>& samples, const std::vector<double>& tolerance) {
  for (size_t i = 0; i < samples.size(); ++i)
    samples[i].weight = 1.0 / (tolerance[i] * tolerance[i]);
}

// Minimises max_i |r_i| / tolerance[i] (Lawson, from the 1/tol^2 fit).
MinimaxSurface FitMinimax(const std::string& context,
                          const PolynomialBasis& basis,
                          HistoryTerms history,
                          std::vector<SurfaceSample> samples,
                          const std::vector<double>& tolerance) {
  WeighByTolerance(samples, tolerance);
  std::vector<double> ratio(samples.size());
  MinimaxSurface best;
  best.estimate = FitSurface(context, basis, samples, history);
  best.first_worst_ratio = best.worst_ratio = WorstRatio(best.estimate, samples, tolerance, ratio);
  for (int k = 0; k < kLawsonIterations; ++k) {
    double sum = 0.0;
    for (size_t i = 0; i < samples.size(); ++i) {
      samples[i].weight *= ratio[i];
      sum += samples[i].weight;
    }
    if (!(sum > 0.0)) break;  // an exact fit: nothing left to reweigh
    for (SurfaceSample& s : samples) s.weight = std::max(s.weight / sum, 1e-12);
    SurfaceEstimate next = FitSurface(context, basis, samples, history);
    const double worst = WorstRatio(next, samples, tolerance, ratio);
    if (worst < best.worst_ratio) {
      best.estimate = std::move(next);
      best.worst_ratio = worst;
    }
  }
  return best;
}

// Temperature order by held-out temperatures: for each candidate degree q of y (3 up to the
// firmware's 5, and at most the number of chamber temperatures less 2, so that every fold still
// determines the surface), each interior chamber temperature in turn is left out of the
// tolerance-weighted (3, q) fit and the worst |error| / tolerance at its points is taken; the
// score is the worst over the folds, and the lowest score wins. The extremes stay in every fold:
// leaving one out would score extrapolation, which the envelope never asks of the surface.
struct OrderChoice {
  int y_degree = 3;
  std::map<int, double> held_out_worst_ratio;  ///< per candidate degree
};

OrderChoice ChooseYDegree(const std::string& context,
                          std::vector<SurfaceSample> samples,
                          const std::function<double(double)>& tolerance_of) {
  const std::vector<double> tolerance = Tolerances(samples, tolerance_of);
  WeighByTolerance(samples, tolerance);
  const std::set<long long> temperatures_dc = ChamberTemperaturesDc(samples);
  const int max_degree =
      std::min<int>(firmware_model::kSurfaceYDegree, static_cast<int>(temperatures_dc.size()) - 2);
  OrderChoice choice;
  double best_score = std::numeric_limits<double>::infinity();
  for (int q = 3; q <= max_degree; ++q) {
    const PolynomialBasis basis =
        PolynomialBasis::TensorSurface(firmware_model::kSurfaceXDegree, q, "x", "y");
    double score = 0.0;
    for (auto it = std::next(temperatures_dc.begin()); it != std::prev(temperatures_dc.end());
         ++it) {
      std::vector<SurfaceSample> kept;
      std::vector<size_t> held;
      for (size_t i = 0; i < samples.size(); ++i) {
        if (ChamberTemperatureKeyDc(samples[i].chamber_c) == *it) {
          held.push_back(i);
        } else {
          kept.push_back(samples[i]);
        }
      }
      const SurfaceEstimate e =
          FitSurface(fmt::format("{} (y degree {}, {:.1f} degC held out)", context, q, *it / 10.0),
                     basis,
                     kept,
                     HistoryTerms::kPressureAndThermal);
      for (size_t i : held) {
        score = std::max(score, std::abs(Predicted(e, samples[i]) - samples[i].z) / tolerance[i]);
      }
    }
    choice.held_out_worst_ratio[q] = score;
    if (score < best_score) {
      best_score = score;
      choice.y_degree = q;
    }
  }
  return choice;
}

}  // namespace

AdsFitResult FitToleranceAdsStrategy(const std::string& context,
                                     const std::vector<AdsCalibrationPoint>& points) {
  const AdsSurfaceSamples samples = SurfaceSamplesOf(points);
  const PolynomialBasis cubic = PolynomialBasis::ReferenceCubicSurface("x", "y");
  const MinimaxSurface alt =
      FitMinimax(context + ": altitude surface",
                 cubic,
                 HistoryTerms::kNone,
                 samples.altitude,
                 Tolerances(samples.altitude, [](double ft) {
                   return AltitudeToleranceFt(std::clamp(ft, kAdsMinAltitudeFt, kAdsMaxAltitudeFt));
                 }));
  const MinimaxSurface cas =
      FitMinimax(context + ": airspeed surface",
                 cubic,
                 HistoryTerms::kNone,
                 samples.airspeed,
                 Tolerances(samples.airspeed, [](double kt) {
                   return AirspeedToleranceKt(std::clamp(kt, kAdsMinAirspeedKt, kAdsMaxAirspeedKt));
                 }));
  AdsFitResult out = AdsFitFromSurfaces(kToleranceAdsStrategyName, alt.estimate, cas.estimate);
  for (const auto& [d, m] : {std::pair{&out.diagnostics.altitude_ft, &alt},
                             std::pair{&out.diagnostics.airspeed_kt, &cas}}) {
    d->worst_ratio_at_points_weighted_fit = m->first_worst_ratio;
    d->worst_ratio_at_points = m->worst_ratio;
    d->lawson_iterations = kLawsonIterations;
  }
  return out;
}

namespace {

// The pressure-surface samples of both bridges with their recorded hysteresis states and their
// envelope bands, and each point's tolerance carried into Pa by the law's local slope.
struct PressureSamples {
  std::vector<SurfaceSample> ps, qc;
  std::vector<BridgeBands> ps_bands, qc_bands;
};

PressureSamples PressureSamplesOf(const std::vector<AdsCalibrationPoint>& points,
                                  const HysteresisSpans& spans) {
  PressureSamples out;
  const std::vector<PointHistory> history = BridgeHistoryOf(points, spans);
  for (size_t i = 0; i < points.size(); ++i) {
    const AdsCalibrationPoint& p = points[i];
    const PointBands bands = EnvelopeBands(p, spans);
    const BridgeStates& s = history[i].static_bridge;
    out.ps.push_back(
        {p.ps_cnt, p.ps_temp_cnt, p.ps_ref_pa, p.chamber_c, 1.0, s.s_pressure, s.s_thermal});
    out.ps_bands.push_back(bands.static_bridge);
    if (p.airspeed_point) {
      const BridgeStates& t = history[i].pitot_bridge;
      out.qc.push_back(
          {p.pt_cnt, p.pt_temp_cnt, p.qc_ref_pa, p.chamber_c, 1.0, t.s_pressure, t.s_thermal});
      out.qc_bands.push_back(bands.pitot_bridge);
    }
  }
  return out;
}

double StaticTolerancePa(double pa) {
  const double ft =
      std::clamp(fm::IsaAltitudeFtFromStaticPa(pa), kAdsMinAltitudeFt, kAdsMaxAltitudeFt);
  const double ft_per_pa =
      fm::IsaAltitudeFtFromStaticPa(pa - 0.5) - fm::IsaAltitudeFtFromStaticPa(pa + 0.5);
  return AltitudeToleranceFt(ft) / ft_per_pa;
}

double ImpactTolerancePa(double pa) {
  const double kt = std::clamp(fm::CasKtFromImpactPa(pa), kAdsMinAirspeedKt, kAdsMaxAirspeedKt);
  const double kt_per_pa = fm::CasKtFromImpactPa(pa + 0.5) - fm::CasKtFromImpactPa(pa - 0.5);
  return AirspeedToleranceKt(kt) / kt_per_pa;
}

const char* LawName(bool altitude) {
  return altitude ? "ISA altitude from static pressure" : "CAS from impact pressure";
}

}  // namespace

AdsFitResult FitPressureAdsStrategy(const std::string& context,
                                    const std::vector<AdsCalibrationPoint>& points) {
  AdsFitDiagnostics span_diagnostics;
  const HysteresisSpans spans =
      EstimateHysteresisSpans(context, points, HysteresisSpans::Nominal(), &span_diagnostics);
  const PressureSamples samples = PressureSamplesOf(points, spans);
  const std::vector<SurfaceSample>& ps = samples.ps;
  const std::vector<SurfaceSample>& qc = samples.qc;
  const std::vector<BridgeBands>& ps_bands = samples.ps_bands;
  const std::vector<BridgeBands>& qc_bands = samples.qc_bands;
  const std::function<double(double)> ps_tolerance = StaticTolerancePa;
  const std::function<double(double)> qc_tolerance = ImpactTolerancePa;
  const std::string ps_context = context + ": static pressure surface";
  const std::string qc_context = context + ": impact pressure surface";
  auto relative_to_mid = [](std::vector<SurfaceSample> samples,
                            const std::vector<BridgeBands>& bands) {
    for (size_t i = 0; i < samples.size(); ++i) {
      samples[i].s_pressure -= bands[i].pressure.mid;
      samples[i].s_thermal -= bands[i].thermal.mid;
    }
    return samples;
  };
  const std::vector<SurfaceSample> ps_mid = relative_to_mid(ps, ps_bands);
  const std::vector<SurfaceSample> qc_mid = relative_to_mid(qc, qc_bands);
  const OrderChoice ps_order = ChooseYDegree(ps_context, ps_mid, ps_tolerance);
  const OrderChoice qc_order = ChooseYDegree(qc_context, qc_mid, qc_tolerance);
  // Two fits with the states as regressors. The first takes them as recorded, weighted 1/tol^2
  // (least squares, not minimax: the minimax's final weights rest on a few points and leave the
  // half loops barely determined): its surface is the loop's centre, and its coefficients the half
  // loops with standard errors (diagnostics, checked against the truth in the tests). The second
  // takes each point's state relative to the middle of its envelope band, so that its surface reads
  // that middle: the smallest worst error over the envelope's histories. The second's surface is
  // the one exported; its history coefficients also absorb what the polynomial cannot follow of the
  // band's middle, so they are not reported.
  struct CentreAndSurface {
    SurfaceEstimate centre;
    MinimaxSurface surface;
  };
  auto fit = [](const std::string& what,
                const OrderChoice& order,
                std::vector<SurfaceSample> recorded,
                const std::vector<SurfaceSample>& mid,
                const std::function<double(double)>& tolerance_of) {
    const PolynomialBasis basis =
        PolynomialBasis::TensorSurface(fm::kSurfaceXDegree, order.y_degree, "x", "y");
    const std::vector<double> tolerance = Tolerances(recorded, tolerance_of);
    WeighByTolerance(recorded, tolerance);
    return CentreAndSurface{
        FitSurface(what, basis, recorded, HistoryTerms::kPressureAndThermal),
        FitMinimax(what, basis, HistoryTerms::kPressureAndThermal, mid, tolerance)};
  };
  const CentreAndSurface alt = fit(ps_context, ps_order, ps, ps_mid, ps_tolerance);
  const CentreAndSurface cas = fit(qc_context, qc_order, qc, qc_mid, qc_tolerance);
  AdsFitResult out = AdsFitFromSurfaces(
      kPressureAdsStrategyName, alt.surface.estimate, cas.surface.estimate, true);
  for (const auto& [d, m, order, spans_of] :
       {std::tuple{&out.diagnostics.altitude_ft, &alt, &ps_order, &span_diagnostics.altitude_ft},
        std::tuple{&out.diagnostics.airspeed_kt, &cas, &qc_order, &span_diagnostics.airspeed_kt}}) {
    d->worst_ratio_at_points_weighted_fit = m->surface.first_worst_ratio;
    d->worst_ratio_at_points = m->surface.worst_ratio;
    d->lawson_iterations = kLawsonIterations;
    d->held_out_worst_ratio_by_y_degree = order->held_out_worst_ratio;
    // The half loops the centre fit separated, Pa per unit state (c = -FS h / 2 for a loop of
    // h FSO between the branches), and how far its centre fits the points.
    const HysteresisEstimate& h = *m->centre.history;
    SurfaceHysteresisDiagnostics& hd = d->hysteresis.emplace();
    hd.pressure_half_loop_pa = h.pressure;
    hd.pressure_half_loop_se_pa = h.pressure_se;
    hd.thermal_half_loop_pa = h.thermal;
    hd.thermal_half_loop_se_pa = h.thermal_se;
    hd.centre_fit_residual_rms_pa = m->centre.residual_rms;
    d->hysteresis_spans = spans_of->hysteresis_spans;
    d->law = LawName(d == &out.diagnostics.altitude_ft);
  }
  return out;
}

namespace {

// The die temperature as a cubic of the surface's y, T = sum_j k_j (y - y0)^j (degC), by the
// project's least-squares driver over the samples (each at a soak, where the die sits at the
// chamber's temperature plus its self-heating, which the operator does not see: it takes
// differences); y0 is the codes' mean. y is the linearised bridge code, nearly linear in T; the
// cubic takes up what the linearisation's quadratic leaves.
struct DieTemperature {
  double origin_code = 0.0;
  std::array<double, 4> c_per_cnt_power = {};
  double residual_rms_c = 0.0;
};

DieTemperature FitDieTemperature(const std::string& context,
                                 const std::vector<SurfaceSample>& samples) {
  const size_t temperatures = ChamberTemperaturesDc(samples).size();
  if (temperatures < 4) {
    throw DegenerateDesignError(fmt::format(
        "{}: the die temperature's cubic in the bridge code needs 4 chamber temperatures, got {}",
        context,
        temperatures));
  }
  double y0 = 0.0;
  for (const SurfaceSample& s : samples) y0 += s.y_code;
  y0 /= static_cast<double>(samples.size());
  PolynomialObservations obs;
  for (const SurfaceSample& s : samples) {
    obs.x.push_back(s.y_code - y0);
    obs.z.push_back(s.chamber_c);
  }
  const PolynomialFit fit = FitPolynomial(context + ": die temperature against the bridge code",
                                          PolynomialBasis::Univariate(3, "y"),
                                          obs,
                                          WeightKind::kInverseVariance,
                                          ErrorScale::kResidualVariance);
  DieTemperature out;
  out.origin_code = y0;
  for (int j = 0; j < 4; ++j) out.c_per_cnt_power[j] = fit.raw_coefficients(j);
  out.residual_rms_c = fit.fit.residual_rms;
  return out;
}

struct CompensatedSurface {
  SurfaceEstimate centre;  ///< least squares with the recorded states: surface and gains
  fm::HysteresisCompensation hysteresis;
  BridgeLinearisationFit linearisation;  ///< of the bridge code: the surface's y is linearised
  double worst_ratio_at_points = 0.0;    ///< |surface + gains . states - z| / tolerance
  double die_temp_residual_rms_c = 0.0;
};

CompensatedSurface FitCompensated(const std::string& context,
                                  const std::vector<SurfaceSample>& samples,
                                  const std::function<double(double)>& tolerance_of,
                                  double pressure_span_pa,
                                  double thermal_span_c,
                                  OrderChoice* order) {
  const BridgeLinearisationFit linearisation = FitBridgeLinearisation(context, samples);
  const std::vector<SurfaceSample> recorded = Linearised(samples, linearisation.linearisation);
  *order = ChooseYDegree(context, recorded, tolerance_of);
  const PolynomialBasis basis =
      PolynomialBasis::TensorSurface(fm::kSurfaceXDegree, order->y_degree, "x", "y");
  const std::vector<double> tolerance = Tolerances(recorded, tolerance_of);
  std::vector<SurfaceSample> weighted = recorded;
  WeighByTolerance(weighted, tolerance);
  CompensatedSurface out;
  out.linearisation = linearisation;
  out.centre = FitSurface(context, basis, weighted, HistoryTerms::kWithTemperatureSlopes);
  out.centre.surface.y_linearisation = linearisation.linearisation;  // fitted in s: takes raw y
  const HysteresisEstimate& h = *out.centre.history;
  for (size_t i = 0; i < samples.size(); ++i) {
    const SurfaceSample& s = samples[i];
    out.worst_ratio_at_points = std::max(out.worst_ratio_at_points,
                                         std::abs(Predicted(out.centre, s) - s.z) / tolerance[i]);
  }
  const DieTemperature die = FitDieTemperature(context, recorded);
  static_assert(kHysteresisReferenceC == fm::kHysteresisGainReferenceC);
  out.hysteresis = {h.pressure,
                    h.pressure_per_c,
                    pressure_span_pa,
                    h.thermal,
                    h.thermal_per_c,
                    thermal_span_c,
                    die.origin_code,
                    die.c_per_cnt_power};
  out.die_temp_residual_rms_c = die.residual_rms_c;
  return out;
}

}  // namespace

namespace {

// One bridge's spans: the cost of a candidate is the tolerance-weighted residual sum of squares
// of the bridge's centre fit (surface of degree (3, q) in the linearised code, q chosen at the
// starting spans; gains and their temperature slopes) with the states those spans give.
SpanFit FitBridgeSpans(const std::string& context,
                       const std::vector<AdsCalibrationPoint>& points,
                       std::vector<SurfaceSample> samples,
                       const std::function<double(double)>& tolerance_of,
                       const HysteresisSpans& start,
                       bool static_bridge) {
  const BridgeLinearisationFit linearisation = FitBridgeLinearisation(context, samples);
  samples = Linearised(samples, linearisation.linearisation);
  const int y_degree = ChooseYDegree(context, samples, tolerance_of).y_degree;
  const PolynomialBasis basis =
      PolynomialBasis::TensorSurface(fm::kSurfaceXDegree, y_degree, "x", "y");
  WeighByTolerance(samples, Tolerances(samples, tolerance_of));
  auto cost = [&](double pressure_span, double thermal_span_c) {
    HysteresisSpans spans = start;
    (static_bridge ? spans.static_pressure_pa : spans.impact_pressure_pa) = pressure_span;
    (static_bridge ? spans.static_temperature_c : spans.pitot_temperature_c) = thermal_span_c;
    const std::vector<PointHistory> history = BridgeHistoryOf(points, spans);
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      if (!static_bridge && !points[i].airspeed_point) continue;
      const BridgeStates& b = static_bridge ? history[i].static_bridge : history[i].pitot_bridge;
      samples[k].s_pressure = b.s_pressure;
      samples[k].s_thermal = b.s_thermal;
      ++k;
    }
    const SurfaceEstimate e =
        FitSurface(context, basis, samples, HistoryTerms::kWithTemperatureSlopes);
    double sum = 0.0;
    for (const SurfaceSample& s : samples) sum += s.weight * std::pow(Predicted(e, s) - s.z, 2);
    return sum;
  };
  const int parameters = static_cast<int>(basis.size()) + 4 + 2;  // surface, gains, slopes, spans
  return FitHysteresisSpans(cost,
                            static_bridge ? start.static_pressure_pa : start.impact_pressure_pa,
                            static_bridge ? start.static_temperature_c : start.pitot_temperature_c,
                            std::max(1, static_cast<int>(samples.size()) - parameters));
}

HysteresisSpanDiagnostics SpanDiagnostics(const SpanFit& f) {
  return {f.pressure_span,
          f.pressure_span_se,
          f.thermal_span_c,
          f.thermal_span_c_se,
          f.cost_at_start,
          f.cost,
          f.at_search_edge};
}

}  // namespace

HysteresisSpans EstimateHysteresisSpans(const std::string& context,
                                        const std::vector<AdsCalibrationPoint>& points,
                                        const HysteresisSpans& start,
                                        AdsFitDiagnostics* diagnostics) {
  const PressureSamples samples = PressureSamplesOf(points, start);
  const SpanFit ps = FitBridgeSpans(context + ": static bridge's hysteresis spans",
                                    points,
                                    samples.ps,
                                    StaticTolerancePa,
                                    start,
                                    true);
  const SpanFit qc = FitBridgeSpans(context + ": pitot bridge's hysteresis spans",
                                    points,
                                    samples.qc,
                                    ImpactTolerancePa,
                                    start,
                                    false);
  if (diagnostics != nullptr) {
    diagnostics->altitude_ft.hysteresis_spans = SpanDiagnostics(ps);
    diagnostics->airspeed_kt.hysteresis_spans = SpanDiagnostics(qc);
  }
  return {ps.pressure_span, qc.pressure_span, ps.thermal_span_c, qc.thermal_span_c};
}

AdsFitResult FitHysteresisAdsStrategy(const std::string& context,
                                      const std::vector<AdsCalibrationPoint>& points,
                                      const HysteresisSpans& start,
                                      SpanChoice span_choice) {
  AdsFitDiagnostics span_diagnostics;
  const HysteresisSpans spans =
      span_choice == SpanChoice::kEstimated
          ? EstimateHysteresisSpans(context, points, start, &span_diagnostics)
          : start;
  const PressureSamples samples = PressureSamplesOf(points, spans);
  OrderChoice ps_order, qc_order;
  const CompensatedSurface alt = FitCompensated(context + ": static pressure surface",
                                                samples.ps,
                                                StaticTolerancePa,
                                                spans.static_pressure_pa,
                                                spans.static_temperature_c,
                                                &ps_order);
  const CompensatedSurface cas = FitCompensated(context + ": impact pressure surface",
                                                samples.qc,
                                                ImpactTolerancePa,
                                                spans.impact_pressure_pa,
                                                spans.pitot_temperature_c,
                                                &qc_order);
  AdsFitResult out = AdsFitFromSurfaces(kHysteresisAdsStrategyName, alt.centre, cas.centre, true);
  out.constants.altitude_ft.hysteresis = alt.hysteresis;
  out.constants.airspeed_kt.hysteresis = cas.hysteresis;
  fm::AdsCalibrationConstants se = out.constants;
  se.altitude_ft.coeff_xy = alt.centre.coeff_se;
  se.airspeed_kt.coeff_xy = cas.centre.coeff_se;
  for (const auto& [surface, c] :
       {std::pair{&se.altitude_ft, &alt}, std::pair{&se.airspeed_kt, &cas}}) {
    const HysteresisEstimate& h = *c->centre.history;
    surface->hysteresis.pressure_gain = h.pressure_se;
    surface->hysteresis.pressure_gain_per_c = h.pressure_per_c_se;
    surface->hysteresis.thermal_gain = h.thermal_se;
    surface->hysteresis.thermal_gain_per_c = h.thermal_per_c_se;
    surface->hysteresis.die_temp_c.fill(std::numeric_limits<double>::quiet_NaN());  // not carried
    surface->y_linearisation.curvature_per_code = c->linearisation.curvature_se_per_code;
  }
  out.standard_errors = AdsStandardErrorsJson(se);
  for (const auto& [d, c, order, spans_of] :
       {std::tuple{&out.diagnostics.altitude_ft, &alt, &ps_order, &span_diagnostics.altitude_ft},
        std::tuple{&out.diagnostics.airspeed_kt, &cas, &qc_order, &span_diagnostics.airspeed_kt}}) {
    d->worst_ratio_at_points = c->worst_ratio_at_points;
    d->held_out_worst_ratio_by_y_degree = order->held_out_worst_ratio;
    const HysteresisEstimate& h = *c->centre.history;
    d->hysteresis =
        SurfaceHysteresisDiagnostics{.pressure_half_loop_pa = h.pressure,
                                     .pressure_half_loop_se_pa = h.pressure_se,
                                     .thermal_half_loop_pa = h.thermal,
                                     .thermal_half_loop_se_pa = h.thermal_se,
                                     .pressure_half_loop_pa_per_c = h.pressure_per_c,
                                     .thermal_half_loop_pa_per_c = h.thermal_per_c,
                                     .centre_fit_residual_rms_pa = c->centre.residual_rms,
                                     .die_temperature_residual_rms_c = c->die_temp_residual_rms_c};
    const BridgeLinearisationFit& l = c->linearisation;
    d->bridge_linearisation = BridgeLinearisationDiagnostics{l.linearisation.curvature_per_code,
                                                             l.curvature_se_per_code,
                                                             l.slope_cnt_per_c,
                                                             l.residual_rms_c};
    d->law = LawName(d == &out.diagnostics.altitude_ft);
    d->hysteresis_spans = spans_of->hysteresis_spans;
  }
  return out;
}

AdsFitResult FitAdsStrategy(const std::string& name,
                            const std::string& context,
                            const std::vector<AdsCalibrationPoint>& points) {
  if (name == kReferenceAdsStrategyName) return FitReferenceAdsStrategy(context, points);
  if (name == kToleranceAdsStrategyName) return FitToleranceAdsStrategy(context, points);
  if (name == kPressureAdsStrategyName) return FitPressureAdsStrategy(context, points);
  if (name == kHysteresisAdsStrategyName) return FitHysteresisAdsStrategy(context, points);
  throw std::invalid_argument("unknown ADS strategy '" + name + "' (known: " +
                              kReferenceAdsStrategyName + ", " + kToleranceAdsStrategyName + ", " +
                              kPressureAdsStrategyName + ", " + kHysteresisAdsStrategyName + ")");
}

}  // namespace adahrs::calib
