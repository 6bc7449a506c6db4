// Envelope sweeps of the fixed-point compensators against the double reference: temperature
// -40..85 C, rates +-150 deg/s, +-10 g, altitude -1,000..50,000 ft, airspeed 30..450 kt, with
// realistic constants. Budgets (10 % of the accuracy budget, asserted): 0.1 mg,
// 0.0015 deg/s, 1.5 ft, 0.1 kt; thermal mode: 0.1 mg at 25 g/duty = 4e-6 duty, 0.0015 deg/s at
// 20,972 counts per deg/s = 31 counts. Cycle budgets (docs/firmware-compensator.md "Cycle table"):
// <= 2,500 per IMU frame, format 2 or 3, <= 3,000 per ADS frame, with operand MOVs, loop control
// and shift loads charged as a compiler emits them. The IMU sweep also holds the exporter's
// worst-case bounds against the measured errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "firmware_model/constants_exporter.h"
#include "firmware_model/reference_compensator.h"
#include "firmware_model/unit_firmware.h"
#include "tests/firmware_model/realistic_constants.h"

namespace adahrs::firmware_model {
namespace {

using testing::RealisticAds;
using testing::RealisticImu;
using testing::SynthesiseAds;
using testing::SynthesiseImu;

constexpr double kBudgetAccel_g = 1e-4;
constexpr double kBudgetAccel_mps2 = 1e-4 * 9.80665;
constexpr double kBudgetRate_dps = 0.0015;
constexpr double kBudgetDuty = 1e-4 / 25.0;
constexpr double kBudgetGyroCounts = 0.0015 * 20972.0;

// Format 2 (the reference method's stages) and format 3 (with the scale-temperature stages).
class ImuSweep : public ::testing::TestWithParam<bool> {};

INSTANTIATE_TEST_SUITE_P(CompensatorSweep,
                         ImuSweep,
                         ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Format3" : "Format2"; });

TEST_P(ImuSweep, WithinBudgetOverEnvelope) {
  constexpr ImuCompensationMode kModes[] = {ImuCompensationMode::kRaw,
                                            ImuCompensationMode::kThermal,
                                            ImuCompensationMode::kSensorCalibrated,
                                            ImuCompensationMode::kFullyCalibrated};
  double worst[4][9] = {};
  ImuExportReport bound{};  // the exporter's worst-case bounds, largest over the units
  uint32_t max_cycles = 0;
  for (uint64_t unit = 0; unit < 4; ++unit) {
    const ImuCalibrationConstants cal =
        GetParam() ? testing::WithScaleTemperature(RealisticImu(1000 + unit), 500 + unit)
                   : RealisticImu(1000 + unit);
    const ImuExport exported = ExportImuConstants(cal);
    bound.accel_g = std::max(bound.accel_g, exported.report.accel_g);
    bound.rate_dps = std::max(bound.rate_dps, exported.report.rate_dps);
    bound.accel_mps2 = std::max(bound.accel_mps2, exported.report.accel_mps2);
    bound.rate_full_dps = std::max(bound.rate_full_dps, exported.report.rate_full_dps);
    common::Rng rng(common::Rng::Derive(77, unit));
    for (int i = 0; i < 1500; ++i) {
      // Corners of the envelope first, then uniform draws inside it.
      const double temp_c = i < 2 ? (i == 0 ? -40.0 : 85.0) : rng.Uniform(-40.0, 85.0);
      std::array<double, 3> f_B_g{}, w_dps{};
      for (int a = 0; a < 3; ++a) {
        f_B_g[a] = i < 2 ? (i == 0 ? 10.0 : -10.0) : rng.Uniform(-10.0, 10.0);
        w_dps[a] = i < 2 ? (i == 0 ? -150.0 : 150.0) : rng.Uniform(-150.0, 150.0);
      }
      const ImuRawFrame raw = SynthesiseImu(cal, f_B_g, w_dps, temp_c, &rng);
      for (int m = 0; m < 4; ++m) {
        DspEngine engine;
        ImuCompensatedFrame frame{};
        ImuCompensate(&engine, exported.constants, kModes[m], raw, &frame);
        ASSERT_EQ(frame.flags, 0) << "mode " << m << " frame " << i;
        if (kModes[m] == ImuCompensationMode::kFullyCalibrated) {
          max_cycles = std::max(max_cycles, engine.cycles());
        }
        const auto fixed = ImuFrameToDouble(kModes[m], frame);
        const auto ref = ImuReference(cal, kModes[m], raw);
        for (int k = 0; k < 9; ++k)
          worst[m][k] = std::max(worst[m][k], std::fabs(fixed[k] - ref[k]));
      }
    }
  }
  auto max_of = [&](int m, int from, int to) {
    return *std::max_element(worst[m] + from, worst[m] + to);
  };
  std::printf(
      "IMU (format %d) worst |fixed - double|: raw duty %.3g, raw counts %.3g; thermal duty %.3g, "
      "counts %.3g; sensor accel %.3g g, rate %.3g dps; full A %.3g m/s^2, G %.3g dps, "
      "half-diff %.3g g; max cycles %u\n",
      GetParam() ? 3 : 2,
      max_of(0, 0, 6),
      max_of(0, 6, 9),
      max_of(1, 0, 6),
      max_of(1, 6, 9),
      max_of(2, 0, 6),
      max_of(2, 6, 9),
      max_of(3, 0, 3),
      max_of(3, 3, 6),
      max_of(3, 6, 9),
      max_cycles);
  // Raw: the duty is floor(U 2^31), so within one Q31 LSB; gyro counts are exact.
  EXPECT_LE(max_of(0, 0, 6), std::ldexp(1.0, -31));
  EXPECT_EQ(max_of(0, 6, 9), 0.0);
  EXPECT_LE(max_of(1, 0, 6), kBudgetDuty);
  EXPECT_LE(max_of(1, 6, 9), kBudgetGyroCounts);
  EXPECT_LE(max_of(2, 0, 6), kBudgetAccel_g);
  EXPECT_LE(max_of(2, 6, 9), kBudgetRate_dps);
  EXPECT_LE(max_of(3, 0, 3), kBudgetAccel_mps2);
  EXPECT_LE(max_of(3, 3, 6), kBudgetRate_dps);
  EXPECT_LE(max_of(3, 6, 9), kBudgetAccel_g);
  std::printf(
      "IMU (format %d) exporter bounds: sensor accel %.3g g, rate %.3g dps; full A %.3g "
      "m/s^2, G %.3g dps\n",
      GetParam() ? 3 : 2,
      bound.accel_g,
      bound.rate_dps,
      bound.accel_mps2,
      bound.rate_full_dps);
  EXPECT_LE(max_of(2, 0, 6), bound.accel_g);
  EXPECT_LE(max_of(2, 6, 9), bound.rate_dps);
  EXPECT_LE(max_of(3, 0, 3), bound.accel_mps2);
  EXPECT_LE(max_of(3, 3, 6), bound.rate_full_dps);
  EXPECT_LE(max_cycles, 2500u);
}

// Both forms: surfaces of altitude and airspeed themselves (the reference method), and surfaces of
// pressure followed by the ISA and CAS laws (the double reference applies the exact laws, so the
// difference includes the target's table interpolation and its 1/128 kt square root).
class AdsSweep : public ::testing::TestWithParam<bool> {};

INSTANTIATE_TEST_SUITE_P(CompensatorSweep,
                         AdsSweep,
                         ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "PressureLaws" : "Direct"; });

TEST_P(AdsSweep, WithinBudgetOverEnvelope) {
  const AdsCalibrationConstants cal = GetParam() ? testing::RealisticPressureAds() : RealisticAds();
  const AdsExport exported = ExportAdsConstants(cal);
  common::Rng rng(4242);
  double worst_alt_ft = 0, worst_cas_kt = 0;
  uint32_t max_cycles = 0;
  AdsHysteresisState state;
  AdsHysteresisReset(&state);
  for (int i = 0; i < 4000; ++i) {
    const double alt_ft = i < 2 ? (i == 0 ? -1000.0 : 50000.0) : rng.Uniform(-1000.0, 50000.0);
    const double cas_kt = i < 2 ? (i == 0 ? 30.0 : 450.0) : rng.Uniform(30.0, 450.0);
    const double temp_c = i < 2 ? (i == 0 ? -40.0 : 85.0) : rng.Uniform(-40.0, 85.0);
    const AdsRawFrame raw = SynthesiseAds(alt_ft, cas_kt, temp_c);
    DspEngine engine;
    AdsCompensatedFrame frame{};
    AdsCompensate(&engine, exported.constants, AdsCompensationMode::kSurface, raw, &state, &frame);
    ASSERT_EQ(frame.flags, 0) << "frame " << i;
    max_cycles = std::max(max_cycles, engine.cycles());
    const auto fixed = AdsFrameToDouble(AdsCompensationMode::kSurface, frame);
    // The reference is given the operators' states (their law: preisach_q15_test.cc).
    constexpr double kQ15 = 1.0 / 32768.0;
    const AdsReferenceStates states{state.static_pressure.state_q15 * kQ15,
                                    state.static_thermal.state_q15 * kQ15,
                                    state.pitot_pressure.state_q15 * kQ15,
                                    state.pitot_thermal.state_q15 * kQ15};
    const auto ref = AdsReference(cal, AdsCompensationMode::kSurface, raw, states);
    worst_alt_ft = std::max(worst_alt_ft, std::fabs(fixed[0] - ref[0]));
    worst_cas_kt = std::max(worst_cas_kt, std::fabs(fixed[1] - ref[1]));
  }
  std::printf(
      "ADS worst |fixed - double|: altitude %.3g ft, airspeed %.3g kt; exporter bounds "
      "%.3g ft, %.3g kt; max cycles %u\n",
      worst_alt_ft,
      worst_cas_kt,
      exported.report.altitude_ft,
      exported.report.airspeed_kt,
      max_cycles);
  EXPECT_LE(worst_alt_ft, 1.5);
  EXPECT_LE(worst_cas_kt, 0.1);
  EXPECT_LE(worst_alt_ft, exported.report.altitude_ft);
  EXPECT_LE(worst_cas_kt, exported.report.airspeed_kt);
  EXPECT_LE(max_cycles, 3000u);
}

}  // namespace
}  // namespace adahrs::firmware_model

namespace adahrs::firmware_model {
namespace {

// The thermal polynomial is normalised to the temperature span its fit covers (with 25 % margin,
// rounded up to a power of two), not to the whole uint16 count domain; beyond that range the
// target holds xi at its end value and flags the input, and a span that is not a span is refused.
TEST(ThermalSpan, NormalisedToTheFittedSpanAndHeldBeyondIt) {
  const ImuCalibrationConstants cal = RealisticImu(3);
  const ImuExport exported = ExportImuConstants(cal);
  for (int ch = 0; ch < kImuChannels; ++ch) {
    SCOPED_TRACE(ch);
    const ThermalFit& f = cal.thermal[ch];
    const InputNormQ31& norm = exported.constants.thermal[ch].temp_norm;
    EXPECT_NEAR(norm.centre, 0.5 * (f.temp_min_cnt + f.temp_max_cnt), 0.5);
    const double needed_half_range = 1.25 * 0.5 * (f.temp_max_cnt - f.temp_min_cnt);
    EXPECT_GE(std::ldexp(1.0, norm.shift), needed_half_range);
    EXPECT_LT(std::ldexp(1.0, norm.shift - 1), needed_half_range);
  }

  const InputNormQ31& norm = exported.constants.thermal[0].temp_norm;
  common::Rng rng(8);
  ImuRawFrame raw = SynthesiseImu(cal, {0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}, 85.0, &rng);
  auto thermal_frame = [&](uint16_t temp_cnt) {
    for (uint16_t& t : raw.temp_cnt) t = temp_cnt;
    DspEngine engine;
    ImuCompensatedFrame frame{};
    ImuCompensate(&engine, exported.constants, ImuCompensationMode::kThermal, raw, &frame);
    return frame;
  };
  const auto edge_cnt = static_cast<uint16_t>(norm.centre + (1 << norm.shift));
  const ImuCompensatedFrame inside = thermal_frame(static_cast<uint16_t>(norm.centre + 1000));
  EXPECT_EQ(inside.flags & kFlagInputSaturated, 0);
  const ImuCompensatedFrame at_edge = thermal_frame(edge_cnt);
  const ImuCompensatedFrame beyond = thermal_frame(static_cast<uint16_t>(edge_cnt + 3000));
  EXPECT_NE(beyond.flags & kFlagInputSaturated, 0);
  for (int i = 0; i < kImuChannels; ++i) EXPECT_EQ(beyond.value[i], at_edge.value[i]) << i;

  ImuCalibrationConstants bad = cal;
  bad.thermal[4].temp_max_cnt = bad.thermal[4].temp_min_cnt;
  EXPECT_THAT([&] { ExportImuConstants(bad); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("thermal block 0x05 (channel 4): temperature span")));
}

// The instruction mix of one frame. Structural truth: a fully calibrated IMU frame does
// 3 x 9 thermal + 6 accel-scale + 3 x 3 gyro + 2 x 9 matrix = 60 Q31 multiplies (one MPY and two
// MUL.SU each) and 2 DIV.UD per accelerometer channel; an ADS frame 2 x (4 x 5 + 3) = 46 (four
// b_k(y) of degree 5, then the cubic in x) plus, per output, 3 for the die temperature's cubic
// and 2 gain x state products: 56; once the hysteresis operators have started (from the second
// frame), 4 x 3 more: each operator's travel (a Q31 multiply), t^2 and the smoothstep (one MPY
// each; the state's product is an MSC).
// Runs one fully calibrated IMU frame, prints its instruction mix and the other modes' cycles,
// and returns the engine of the fully calibrated frame.
DspEngine ImuFrameMix(const char* title, const ImuConstants& constants, const ImuRawFrame& raw) {
  DspEngine engine;
  ImuCompensatedFrame frame{};
  ImuCompensate(&engine, constants, ImuCompensationMode::kFullyCalibrated, raw, &frame);
  std::printf(
      "IMU fully calibrated frame, %s: %u instructions, %u cycles (%.2f %% of 30 MIPS at "
      "100 Hz)\n",
      title,
      engine.instructions(),
      engine.cycles(),
      100.0 * engine.cycles() * 100.0 / 30e6);
  for (uint8_t op = 0; op < static_cast<uint8_t>(DspOp::kCount); ++op) {
    const DspOp o = static_cast<DspOp>(op);
    if (engine.op_count(o) > 0) {
      std::printf("  %-12s x%4u  %2u cy  = %5u\n",
                  DspOpName(o),
                  engine.op_count(o),
                  DspOpCycles(o),
                  engine.op_count(o) * DspOpCycles(o));
    }
  }
  for (uint8_t m = 0; m < 3; ++m) {
    DspEngine e;
    ImuCompensate(&e, constants, static_cast<ImuCompensationMode>(m), raw, &frame);
    std::printf("IMU %s mode %u: %u cycles\n", title, m, e.cycles());
  }
  return engine;
}

TEST(CompensatorCycles, InstructionMixMatchesTheAlgorithm) {
  common::Rng rng(5);
  const ImuRawFrame raw = testing::SynthesiseImu(
      testing::RealisticImu(1), {0.0, 0.0, 1.0}, {10.0, 0.0, 0.0}, 25.0, &rng);
  const DspEngine engine =
      ImuFrameMix("format 2", ExportImuConstants(testing::RealisticImu(1)).constants, raw);
  EXPECT_EQ(engine.op_count(DspOp::kMpy), 60u);
  EXPECT_EQ(engine.op_count(DspOp::kMulSU), 120u);
  EXPECT_EQ(engine.op_count(DspOp::kDivUD), 12u);
  // Format 3: the thermal Horner steps become Q31 x Q15 (one MPY and one MUL.SU each, 27 + 27);
  // tau^2 and tau^3 per sensor (6 MPY); per channel delta's MPY and two MACs, and y delta's MUL.SU
  // and MAC; q's two MPYs per axis; GS's MPY and two MACs per row. The 6 accel-scale, 9 gyro-cubic
  // and 18 matrix Q31 multiplies are format 2's.
  const DspEngine engine3 = ImuFrameMix(
      "format 3",
      ExportImuConstants(testing::WithScaleTemperature(testing::RealisticImu(1), 2)).constants,
      raw);
  EXPECT_EQ(engine3.op_count(DspOp::kMpy), 27u + 6u + 9u + 6u + 3u + 33u);
  EXPECT_EQ(engine3.op_count(DspOp::kMulSU), 27u + 9u + 2u * 33u);
  EXPECT_EQ(engine3.op_count(DspOp::kMac), 9u * 3u + 3u * 2u);
  AdsCalibrationConstants with_hysteresis = testing::RealisticAds();
  with_hysteresis.altitude_ft.hysteresis = testing::RealisticPressureAds().altitude_ft.hysteresis;
  with_hysteresis.altitude_ft.hysteresis.pressure_gain = -2.0;  // ft: the surface is direct
  with_hysteresis.altitude_ft.hysteresis.pressure_span = 6000.0;
  with_hysteresis.airspeed_kt.hysteresis = testing::RealisticPressureAds().airspeed_kt.hysteresis;
  with_hysteresis.airspeed_kt.hysteresis.pressure_gain = -0.5;  // kt
  with_hysteresis.airspeed_kt.hysteresis.pressure_span = 80.0;
  const AdsExport ads = ExportAdsConstants(with_hysteresis);
  DspEngine ads_engine;
  AdsCompensatedFrame ads_frame{};
  AdsHysteresisState ads_state;
  AdsHysteresisReset(&ads_state);
  AdsCompensate(&ads_engine,
                ads.constants,
                AdsCompensationMode::kSurface,
                testing::SynthesiseAds(5000.0, 200.0, 25.0),
                &ads_state,
                &ads_frame);
  EXPECT_EQ(ads_engine.op_count(DspOp::kMpy), 56u);
  DspEngine moving_engine;
  AdsCompensate(&moving_engine,
                ads.constants,
                AdsCompensationMode::kSurface,
                testing::SynthesiseAds(6000.0, 210.0, 26.0),
                &ads_state,
                &ads_frame);
  EXPECT_EQ(moving_engine.op_count(DspOp::kMpy), 68u);
  // Each of the four moving operators adds its weight to the branch's start state once (ADD of a
  // word); a still operator returns before.
  EXPECT_EQ(moving_engine.op_count(DspOp::kAddWordAcc) - ads_engine.op_count(DspOp::kAddWordAcc),
            4u);
  EXPECT_EQ(moving_engine.op_count(DspOp::kMsc), 0u);
  std::printf(
      "ADS surface frame: %u instructions, %u cycles (%.2f %% of 30 MIPS at 100 Hz); "
      "with the operators moving: %u cycles\n",
      ads_engine.instructions(),
      ads_engine.cycles(),
      100.0 * ads_engine.cycles() * 100.0 / 30e6,
      moving_engine.cycles());
}

}  // namespace
}  // namespace adahrs::firmware_model
