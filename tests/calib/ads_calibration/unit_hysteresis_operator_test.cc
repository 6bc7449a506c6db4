// The calibration's hysteresis operator against the unit's own (firmware_model/target/
// preisach_q15.h): driven by the same random pressure history, including reversals deep enough
// to fill the unit's branch stack, the two agree within the Q15 operator's rounding.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "calib/ads_calibration/unit_hysteresis_operator.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::calib {
namespace {

TEST(UnitHysteresisOperator, FollowsTheUnitsFixedPointOperator) {
  constexpr double kSpanPa = 20000.0;
  constexpr int kExponent = 18;  // inputs below 2^17 Pa
  int e = 0;
  const double m = std::frexp(1.0 / kSpanPa, &e);
  const firmware_model::CoeffQ31 inv_span{
      static_cast<int32_t>(std::lround(std::ldexp(m, 31) - 1.0)), static_cast<int8_t>(e)};
  firmware_model::PreisachQ15 unit;
  firmware_model::PreisachResetQ15(&unit);
  UnitHysteresisOperator calib(kSpanPa);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(-8000.0, 8000.0);
  double p = 60000.0, worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    p = std::clamp(p + step(rng) * (i % 50 < 25 ? 1.0 : 0.05), 10000.0, 110000.0);
    const int32_t mantissa = static_cast<int32_t>(std::lround(std::ldexp(p, 31 - kExponent)));
    firmware_model::DspEngine engine;
    const double s_unit = std::ldexp(
        firmware_model::PreisachUpdateQ15(&engine, &unit, mantissa, kExponent, inv_span), -15);
    const double s_calib = calib.Update(std::ldexp(static_cast<double>(mantissa), kExponent - 31));
    worst = std::max(worst, std::abs(s_unit - s_calib));
  }
  // The unit's bound against the law (tests/firmware_model/preisach_q15_test.cc): each branch
  // start stores a rounded state and the Q15 weight is rounded, so errors add up over the stack
  // (measured 2026-11-26: 3.9e-4, 13 LSB).
  EXPECT_LT(worst, 5e-4);
}

}  // namespace
}  // namespace adahrs::calib
