#include "calib/ads_calibration/tolerance_ads_strategy.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "calib/evaluation/ads_tolerance.h"
#include "firmware_model/air_data_law.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

struct MinimaxSurface {
  SurfaceEstimate estimate;
  double first_worst_ratio = 0.0;  ///< of the 1/tol^2 fit
  double worst_ratio = 0.0;        ///< of the kept iterate
};

double WorstRatio(const SurfaceEstimate& e, const std::vector<SurfaceSample>& samples,
                  const std::vector<double>& tolerance, std::vector<double>& ratio) {
  double worst = 0.0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const double fitted =
        firmware_model::EvaluateSurfaceFit(e.surface, samples[i].x_code, samples[i].y_code);
    ratio[i] = std::abs(fitted - samples[i].z) / tolerance[i];
    worst = std::max(worst, ratio[i]);
  }
  return worst;
}

MinimaxSurface FitMinimax(const std::string& context, std::vector<SurfaceSample> samples,
                          const std::function<double(double)>& tolerance_of) {
  std::vector<double> tolerance(samples.size()), ratio(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) {
    tolerance[i] = tolerance_of(samples[i].z);
    samples[i].weight = 1.0 / (tolerance[i] * tolerance[i]);
  }
  MinimaxSurface best;
  best.estimate = FitReferenceSurface(context, samples);
  best.first_worst_ratio = best.worst_ratio = WorstRatio(best.estimate, samples, tolerance, ratio);
  for (int k = 0; k < kLawsonIterations; ++k) {
    double sum = 0.0;
    for (size_t i = 0; i < samples.size(); ++i) {
      samples[i].weight *= ratio[i];
      sum += samples[i].weight;
    }
    if (!(sum > 0.0)) break;  // an exact fit: nothing left to reweigh
    for (SurfaceSample& s : samples) s.weight = std::max(s.weight / sum, 1e-12);
    SurfaceEstimate next = FitReferenceSurface(context, samples);
    const double worst = WorstRatio(next, samples, tolerance, ratio);
    if (worst < best.worst_ratio) {
      best.estimate = std::move(next);
      best.worst_ratio = worst;
    }
  }
  return best;
}

}  // namespace

AdsFitResult FitToleranceAdsStrategy(const std::string& context,
                                     const std::vector<AdsCalibrationPoint>& points) {
  const AdsSurfaceSamples samples = SurfaceSamplesOf(points);
  const MinimaxSurface alt = FitMinimax(context + ": altitude surface", samples.altitude, [](double ft) {
    return AltitudeToleranceFt(std::clamp(ft, kAdsMinAltitudeFt, kAdsMaxAltitudeFt));
  });
  const MinimaxSurface cas = FitMinimax(context + ": airspeed surface", samples.airspeed, [](double kt) {
    return AirspeedToleranceKt(std::clamp(kt, kAdsMinAirspeedKt, kAdsMaxAirspeedKt));
  });
  AdsFitResult out = AdsFitFromSurfaces(kToleranceAdsStrategyName, alt.estimate, cas.estimate);
  for (const auto& [key, m] : {std::pair{"altitude_ft", &alt}, std::pair{"airspeed_kt", &cas}}) {
    out.diagnostics[key]["worst_ratio_at_points_weighted_fit"] = m->first_worst_ratio;
    out.diagnostics[key]["worst_ratio_at_points"] = m->worst_ratio;
    out.diagnostics[key]["lawson_iterations"] = kLawsonIterations;
  }
  return out;
}

AdsFitResult FitPressureAdsStrategy(const std::string& context,
                                    const std::vector<AdsCalibrationPoint>& points) {
  std::vector<SurfaceSample> ps, qc;
  for (const AdsCalibrationPoint& p : points) {
    ps.push_back({p.ps_code, p.ps_temp_code, p.ps_ref_pa, p.chamber_c});
    if (p.airspeed_point) qc.push_back({p.pt_code, p.pt_temp_code, p.qc_ref_pa, p.chamber_c});
  }
  namespace fm = firmware_model;
  const MinimaxSurface alt = FitMinimax(context + ": static pressure surface", ps, [](double pa) {
    const double ft = std::clamp(fm::IsaAltitudeFtFromStaticPa(pa), kAdsMinAltitudeFt, kAdsMaxAltitudeFt);
    const double ft_per_pa = fm::IsaAltitudeFtFromStaticPa(pa - 0.5) - fm::IsaAltitudeFtFromStaticPa(pa + 0.5);
    return AltitudeToleranceFt(ft) / ft_per_pa;
  });
  const MinimaxSurface cas = FitMinimax(context + ": impact pressure surface", qc, [](double pa) {
    const double kt = std::clamp(fm::CasKtFromImpactPa(pa), kAdsMinAirspeedKt, kAdsMaxAirspeedKt);
    const double kt_per_pa = fm::CasKtFromImpactPa(pa + 0.5) - fm::CasKtFromImpactPa(pa - 0.5);
    return AirspeedToleranceKt(kt) / kt_per_pa;
  });
  AdsFitResult out = AdsFitFromSurfaces(kPressureAdsStrategyName, alt.estimate, cas.estimate, true);
  for (const auto& [key, m] : {std::pair{"altitude_ft", &alt}, std::pair{"airspeed_kt", &cas}}) {
    out.diagnostics[key]["worst_ratio_at_points_weighted_fit"] = m->first_worst_ratio;
    out.diagnostics[key]["worst_ratio_at_points"] = m->worst_ratio;
    out.diagnostics[key]["lawson_iterations"] = kLawsonIterations;
    out.diagnostics[key]["law"] = key == std::string("altitude_ft") ? "ISA altitude from static pressure"
                                                                    : "CAS from impact pressure";
  }
  return out;
}

AdsFitResult FitAdsStrategy(const std::string& name, const std::string& context,
                            const std::vector<AdsCalibrationPoint>& points) {
  if (name == kReferenceAdsStrategyName) return FitReferenceAdsStrategy(context, points);
  if (name == kToleranceAdsStrategyName) return FitToleranceAdsStrategy(context, points);
  if (name == kPressureAdsStrategyName) return FitPressureAdsStrategy(context, points);
  throw std::invalid_argument("unknown ADS strategy '" + name + "' (known: " +
                              kReferenceAdsStrategyName + ", " + kToleranceAdsStrategyName + ", " +
                              kPressureAdsStrategyName + ")");
}

}  // namespace adahrs::calib
