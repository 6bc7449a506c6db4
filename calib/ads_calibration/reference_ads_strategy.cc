#include "calib/ads_calibration/reference_ads_strategy.h"

#include "calib/constants/constants_file.h"

namespace adahrs::calib {
namespace {

AdsSurfaceDiagnostics SurfaceDiagnostics(const SurfaceEstimate& e, const char* unit) {
  AdsSurfaceDiagnostics d;
  d.unit = unit;
  d.points = e.fit.fit.observations;
  d.terms = e.terms;
  d.y_degree = e.y_degree;
  d.dof = e.fit.fit.dof;
  d.residual_rms = e.residual_rms;
  d.max_abs_residual = e.max_abs_residual;
  return d;
}

}  // namespace

AdsFitResult FitReferenceAdsStrategy(const std::string& context,
                                     const std::vector<AdsCalibrationPoint>& points) {
  const AdsSurfaceSamples samples = SurfaceSamplesOf(points);
  return AdsFitFromSurfaces(kReferenceAdsStrategyName,
                            FitReferenceSurface(context + ": altitude surface", samples.altitude),
                            FitReferenceSurface(context + ": airspeed surface", samples.airspeed));
}

AdsSurfaceSamples SurfaceSamplesOf(const std::vector<AdsCalibrationPoint>& points) {
  AdsSurfaceSamples out;
  for (const AdsCalibrationPoint& p : points) {
    out.altitude.push_back({p.ps_cnt, p.ps_temp_cnt, p.alt_ft, p.chamber_c});
    if (p.airspeed_point) {
      out.airspeed.push_back({p.pt_cnt, p.pt_temp_cnt, p.cas_kt, p.chamber_c});
    }
  }
  return out;
}

AdsFitResult AdsFitFromSurfaces(const std::string& strategy,
                                const SurfaceEstimate& alt,
                                const SurfaceEstimate& cas,
                                bool pressure_laws) {
  AdsFitResult out;
  out.strategy = strategy;
  out.constants.altitude_ft = alt.surface;
  out.constants.airspeed_kt = cas.surface;
  if (pressure_laws) {
    out.constants.altitude_ft.law = firmware_model::SurfaceLaw::kIsaAltitude;
    out.constants.airspeed_kt.law = firmware_model::SurfaceLaw::kCas;
  }
  // The constants' own shape with the coefficients' standard errors (code box and law: null).
  firmware_model::AdsCalibrationConstants se = out.constants;
  se.altitude_ft.coeff_xy = alt.coeff_se;
  se.airspeed_kt.coeff_xy = cas.coeff_se;
  out.standard_errors = AdsStandardErrorsJson(se);
  out.diagnostics = {SurfaceDiagnostics(alt, pressure_laws ? "pa" : "ft"),
                     SurfaceDiagnostics(cas, pressure_laws ? "pa" : "kt")};
  return out;
}

}  // namespace adahrs::calib
