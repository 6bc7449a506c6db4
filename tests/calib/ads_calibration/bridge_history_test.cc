// The hysteresis states the ADS strategy assigns to calibration points (bridge_history.h), against
// the Preisach law written out here by hand (physics.md section 6: along a branch from a reversal
// at state s_ext, s = s_ext - 2 d F(t), F(t) = t^2 (3 - 2 t) over a travel t of the span; the
// virgin curve from a fresh unit, s = -d F(2 t)), and the envelope bands against the histories the
// evaluation applies (ads_evaluation.h).
#include "calib/ads_calibration/bridge_history.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

// State after moving in direction d from a reversal at state s_ext by `travel` (input units).
double AfterReversal(double s_ext, int d, double travel, double span) {
  const double t = std::min(travel / span, 1.0);
  return s_ext - 2.0 * d * t * t * (3.0 - 2.0 * t);
}

AdsCalibrationPoint At(double chamber_c, double ps_pa, double qc_pa) {
  AdsCalibrationPoint p;
  p.chamber_c = chamber_c;
  p.ps_ref_pa = ps_pa;
  p.qc_ref_pa = qc_pa;
  return p;
}

TEST(BridgeHistory, StatesFollowTheReferenceHistoryFromARestingUnit) {
  const HysteresisSpans spans{20000.0, 20000.0, 20.0, 20.0};
  // From the room (25 degC, 101,325 Pa, fresh): cool to -40 (65 degC of travel: +1), climb to a
  // static 81,325 Pa (a fall of 20,000 Pa from the start: +1), then heat by 10 degC (-30 degC:
  // half the span from the reversal at -40) with the static pressure back up by 5,000 Pa.
  const std::vector<AdsCalibrationPoint> points = {
      At(-40.0, 81325.0, 0.0), At(-30.0, 86325.0, 0.0), At(85.0, 86325.0, 30000.0)};
  const std::vector<PointHistory> h = BridgeHistoryOf(points, spans);
  ASSERT_EQ(h.size(), 3u);
  EXPECT_DOUBLE_EQ(h[0].static_bridge.s_thermal, 1.0);
  EXPECT_DOUBLE_EQ(h[0].static_bridge.s_pressure, 1.0);
  EXPECT_DOUBLE_EQ(h[0].pitot_bridge.s_pressure, 0.0);  // impact pressure never moved
  EXPECT_NEAR(h[1].static_bridge.s_thermal, AfterReversal(1.0, +1, 10.0, 20.0), 1e-12);
  EXPECT_NEAR(h[1].static_bridge.s_pressure, AfterReversal(1.0, +1, 5000.0, 20000.0), 1e-12);
  EXPECT_DOUBLE_EQ(h[1].pitot_bridge.s_thermal, h[1].static_bridge.s_thermal);  // one chamber
  EXPECT_DOUBLE_EQ(h[2].static_bridge.s_thermal, -1.0);
  EXPECT_DOUBLE_EQ(h[2].pitot_bridge.s_pressure, -1.0);  // 30,000 Pa of rise: past the span
}

TEST(BridgeHistory, EnvelopeBandIsOneSidedAtTheEndsAndFullInTheMiddle) {
  const double span = 20.0, low = -40.0, high = 85.0;
  // At the cold end every history but "fresh" arrives by cooling (+1): band [0, 1].
  StateBand b = EnvelopeStateBand(low, low, high, span);
  EXPECT_DOUBLE_EQ(b.mid, 0.5);
  EXPECT_DOUBLE_EQ(b.half_width, 0.5);
  // In the middle, heating gives -1 and cooling +1: band [-1, 1].
  b = EnvelopeStateBand(22.5, low, high, span);
  EXPECT_DOUBLE_EQ(b.mid, 0.0);
  EXPECT_DOUBLE_EQ(b.half_width, 1.0);
  // 10 degC above the cold end: heating from -40 has gone half the span, cooling is at +1.
  const double heating = AfterReversal(1.0, +1, 10.0, span);
  b = EnvelopeStateBand(-30.0, low, high, span);
  const double lo = std::min(0.0, heating);
  EXPECT_NEAR(b.mid, 0.5 * (lo + 1.0), 1e-12);
  EXPECT_NEAR(b.half_width, 0.5 * (1.0 - lo), 1e-12);
  // The hot end mirrors the cold one.
  b = EnvelopeStateBand(high, low, high, span);
  EXPECT_DOUBLE_EQ(b.mid, -0.5);
  EXPECT_DOUBLE_EQ(b.half_width, 0.5);
}

// A constants set's spans: each surface's own where it has one, the nominal one where it has none.
TEST(BridgeHistory, SpansOfConstantsFallBackToTheNominalPerSurface) {
  firmware_model::AdsCalibrationConstants c;
  c.altitude_ft.hysteresis.pressure_span = 12000.0;
  c.altitude_ft.hysteresis.thermal_span_c = 15.0;
  const HysteresisSpans spans = HysteresisSpans::Of(c);
  const HysteresisSpans nominal = HysteresisSpans::Nominal();
  EXPECT_EQ(spans.static_pressure_pa, 12000.0);
  EXPECT_EQ(spans.static_temperature_c, 15.0);
  EXPECT_EQ(spans.impact_pressure_pa, nominal.impact_pressure_pa);
  EXPECT_EQ(spans.pitot_temperature_c, nominal.pitot_temperature_c);
  EXPECT_GT(nominal.impact_pressure_pa, 0.0);
}

}  // namespace
}  // namespace adahrs::calib
