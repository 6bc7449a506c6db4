#include "calib/ads_calibration/bridge_history.h"

#include <algorithm>

#include "calib/acceptance/ads_tolerance.h"
#include "calib/ads_calibration/unit_hysteresis_operator.h"
#include "common/air_data.h"
#include "common/atmosphere.h"

namespace adahrs::calib {
namespace {

constexpr double kRoomTemperatureC = 25.0;
// The model-1230 class: 0-15 psi absolute and differential (physics.md section 3.1, R); the
// travel to a full hysteresis state 20 % of full scale and 20 degC (physics.md section 6 rows 4
// and 7 give the loops' size, not their travel: an engineering estimate, E).
constexpr double kFullScalePa = 15.0 * 6894.757293168;
constexpr double kPressureSpanFractionFs = 0.20;
constexpr double kThermalSpanC = 20.0;

}  // namespace

HysteresisSpans HysteresisSpans::Nominal() {
  return {kPressureSpanFractionFs * kFullScalePa,
          kPressureSpanFractionFs * kFullScalePa,
          kThermalSpanC,
          kThermalSpanC};
}

HysteresisSpans HysteresisSpans::Of(const firmware_model::AdsCalibrationConstants& c) {
  const HysteresisSpans nominal = Nominal();
  auto or_nominal = [](double span, double fallback) { return span > 0.0 ? span : fallback; };
  return {or_nominal(c.altitude_ft.hysteresis.pressure_span, nominal.static_pressure_pa),
          or_nominal(c.airspeed_kt.hysteresis.pressure_span, nominal.impact_pressure_pa),
          or_nominal(c.altitude_ft.hysteresis.thermal_span_c, nominal.static_temperature_c),
          or_nominal(c.airspeed_kt.hysteresis.thermal_span_c, nominal.pitot_temperature_c)};
}

std::vector<PointHistory> BridgeHistoryOf(const std::vector<AdsCalibrationPoint>& points,
                                          const HysteresisSpans& spans) {
  UnitHysteresisOperator static_p(spans.static_pressure_pa);
  UnitHysteresisOperator impact_p(spans.impact_pressure_pa);
  UnitHysteresisOperator static_t(spans.static_temperature_c);
  UnitHysteresisOperator pitot_t(spans.pitot_temperature_c);
  static_p.Update(common::kIsaSeaLevelPressure_pa);
  impact_p.Update(0.0);
  static_t.Update(kRoomTemperatureC);
  pitot_t.Update(kRoomTemperatureC);
  std::vector<PointHistory> out;
  out.reserve(points.size());
  for (const AdsCalibrationPoint& p : points) {
    out.push_back({{static_p.Update(p.ps_ref_pa), static_t.Update(p.chamber_c)},
                   {impact_p.Update(p.qc_ref_pa), pitot_t.Update(p.chamber_c)}});
  }
  return out;
}

StateBand EnvelopeStateBand(double x, double low, double high, double span) {
  auto after = [&](double first, double second) {
    UnitHysteresisOperator op(span);
    op.Update(first);
    op.Update(second);
    return op.Update(x);
  };
  const double rising = after(high, low), falling = after(low, high);
  const double lo = std::min({0.0, rising, falling}), hi = std::max({0.0, rising, falling});
  return {0.5 * (lo + hi), 0.5 * (hi - lo)};
}

PointBands EnvelopeBands(const AdsCalibrationPoint& point, const HysteresisSpans& spans) {
  using common::IsaStaticPressurePaFromFt;
  const double ps_low = IsaStaticPressurePaFromFt(kAdsMaxAltitudeFt);
  const double ps_high = IsaStaticPressurePaFromFt(kAdsMinAltitudeFt);
  const double qc_low = common::ImpactPressurePaFromKt(kAdsMinAirspeedKt);
  const double qc_high = common::ImpactPressurePaFromKt(kAdsMaxAirspeedKt);
  auto thermal = [&](double span_c) {
    return EnvelopeStateBand(point.chamber_c, kAdsMinTempC, kAdsMaxTempC, span_c);
  };
  return {{EnvelopeStateBand(point.ps_ref_pa, ps_low, ps_high, spans.static_pressure_pa),
           thermal(spans.static_temperature_c)},
          {EnvelopeStateBand(point.qc_ref_pa, qc_low, qc_high, spans.impact_pressure_pa),
           thermal(spans.pitot_temperature_c)}};
}

}  // namespace adahrs::calib
