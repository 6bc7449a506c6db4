// Block-wise constant access as the maintenance handler uses it: round trip of every block, each
// refusal reason, and that a refused write changes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <utility>

#include "firmware_model/constants_exporter.h"
#include "firmware_model/unit_firmware.h"
#include "tests/firmware_model/realistic_constants.h"

namespace adahrs::firmware_model {
namespace {

TEST(ConstantsBlocks, ImuRoundTripEveryBlock) {
  const ImuConstants source = ExportImuConstants(testing::RealisticImu(5)).constants;
  ImuConstants target;
  ImuConstantsInit(&target);
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockCg; ++id) {
    int16_t words[kImuMaxBlockWords];
    uint8_t count = 0;
    ASSERT_EQ(ImuConstantsReadBlock(&source, id, words, kImuMaxBlockWords, &count),
              ConstantsStatus::kOk);
    EXPECT_EQ(count, ImuConstantsBlockLength(id));
    ASSERT_EQ(ImuConstantsWriteBlock(&target, id, words, count), ConstantsStatus::kOk) << int(id);
  }
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockCg; ++id) {
    int16_t a[kImuMaxBlockWords], b[kImuMaxBlockWords];
    uint8_t na = 0, nb = 0;
    ImuConstantsReadBlock(&source, id, a, kImuMaxBlockWords, &na);
    ImuConstantsReadBlock(&target, id, b, kImuMaxBlockWords, &nb);
    ASSERT_EQ(na, nb);
    EXPECT_EQ(std::memcmp(a, b, na * sizeof(int16_t)), 0) << int(id);
  }
}

TEST(ConstantsBlocks, Format3RoundTripAndRefusals) {
  const ImuConstants source =
      ExportImuConstants(testing::WithScaleTemperature(testing::RealisticImu(5), 6)).constants;
  ASSERT_EQ(source.scale_temperature.enabled, 1);
  ImuConstants target;
  ImuConstantsInit(&target);
  EXPECT_EQ(target.scale_temperature.enabled, 0);
  int16_t words[kImuMaxBlockWords];
  uint8_t count = 0;
  for (uint8_t id = kImuBlockScaleSwitch; id <= kImuBlockLast; ++id) {
    ASSERT_EQ(ImuConstantsReadBlock(&source, id, words, kImuMaxBlockWords, &count),
              ConstantsStatus::kOk);
    EXPECT_EQ(count, ImuConstantsBlockLength(id));
    ASSERT_EQ(ImuConstantsWriteBlock(&target, id, words, count), ConstantsStatus::kOk) << int(id);
    int16_t back[kImuMaxBlockWords];
    uint8_t back_count = 0;
    ImuConstantsReadBlock(&target, id, back, kImuMaxBlockWords, &back_count);
    ASSERT_EQ(back_count, count);
    EXPECT_EQ(std::memcmp(words, back, count * sizeof(int16_t)), 0) << int(id);
  }
  EXPECT_EQ(ImuConstantsBlockLength(kImuBlockLast + 1), 0);

  const ImuConstants before = target;
  ImuConstantsReadBlock(&target, kImuBlockScaleSwitch, words, kImuMaxBlockWords, &count);
  words[0] = 2;  // the switch is 0 or 1
  EXPECT_EQ(ImuConstantsWriteBlock(&target, kImuBlockScaleSwitch, words, count),
            ConstantsStatus::kOutOfRange);
  words[0] = 1;
  words[1 + 2 * kNormWords + 2] = 17;  // sensor 2's shift beyond 16
  EXPECT_EQ(ImuConstantsWriteBlock(&target, kImuBlockScaleSwitch, words, count),
            ConstantsStatus::kOutOfRange);
  ImuConstantsReadBlock(&target, kImuBlockScaleFactorFirst + 4, words, kImuMaxBlockWords, &count);
  words[0] = kScaleFactorExponent + 1;  // F's working exponent is fixed
  EXPECT_EQ(ImuConstantsWriteBlock(&target, kImuBlockScaleFactorFirst + 4, words, count),
            ConstantsStatus::kOutOfRange);
  // q = 0.9375 * 2^-3 = 0.117 g/g^2: beyond 1/16, it could leave the g format at 16 g.
  ImuConstantsReadBlock(&target, kImuBlockAccelQuadratic, words, kImuMaxBlockWords, &count);
  words[3] = 0x7800;
  words[4] = 0;
  words[5] = -3;
  EXPECT_EQ(ImuConstantsWriteBlock(&target, kImuBlockAccelQuadratic, words, count),
            ConstantsStatus::kWouldOverflow);
  words[5] = -25;  // alignment shift -4 - e = 21 beyond one SFTAC
  EXPECT_EQ(ImuConstantsWriteBlock(&target, kImuBlockAccelQuadratic, words, count),
            ConstantsStatus::kOutOfRange);
  // A GS row of 3 deg/s per m/s^2 overflows +-256 deg/s at the rated 99 m/s^2.
  ImuConstantsReadBlock(&target, kImuBlockGs, words, kImuMaxBlockWords, &count);
  words[0] = 0x6000;  // 0.75 * 2^2 = 3
  words[1] = 0;
  words[2] = 2;
  EXPECT_EQ(ImuConstantsWriteBlock(&target, kImuBlockGs, words, count),
            ConstantsStatus::kWouldOverflow);
  EXPECT_EQ(std::memcmp(&target, &before, sizeof(target)), 0);
}

double ValueOf(const CoeffQ31& c) {
  return std::ldexp(static_cast<double>(c.mantissa_q31), c.exponent - 31);
}

// The Q15 forms the compensator runs hold the blocks' values within half an LSB of each mantissa,
// sum within their chains' range, and the exporter derives the same forms as a block write does.
TEST(ConstantsBlocks, Format3RunTimeFormsHoldTheBlocksWithinHalfAnLsb) {
  const ImuConstants source =
      ExportImuConstants(testing::WithScaleTemperature(testing::RealisticImu(5), 6)).constants;
  ImuConstants target;
  ImuConstantsInit(&target);
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockLast; ++id) {
    int16_t words[kImuMaxBlockWords];
    uint8_t count = 0;
    ImuConstantsReadBlock(&source, id, words, kImuMaxBlockWords, &count);
    ASSERT_EQ(ImuConstantsWriteBlock(&target, id, words, count), ConstantsStatus::kOk) << int(id);
  }
  const ScaleTemperatureConstantsQ31& st = target.scale_temperature;
  for (int c = 0; c < kImuChannels; ++c) {
    const ScaleDeltaQ15& d = st.delta[c];
    EXPECT_EQ(std::memcmp(&d, &source.scale_temperature.delta[c], sizeof(d)), 0) << c;
    ASSERT_GE(d.exponent - d.tempco_exponent, 0);
    ASSERT_LE(d.exponent - d.tempco_exponent, 16);
    EXPECT_NEAR(std::ldexp(static_cast<double>(d.d0_q31), d.exponent - 31),
                ValueOf(st.scale[c].coeff[0]) - 1.0,
                std::ldexp(1.0, d.exponent - 32));
    double sum_abs_q31 = std::fabs(static_cast<double>(d.d0_q31));
    for (int k = 1; k <= kImuScaleFactorDegree; ++k) {
      EXPECT_NEAR(std::ldexp(static_cast<double>(d.d_q15[k - 1]), d.tempco_exponent - 15),
                  ValueOf(st.scale[c].coeff[k]),
                  std::ldexp(1.0, d.tempco_exponent - 16));
      sum_abs_q31 += std::ldexp(std::fabs(static_cast<double>(d.d_q15[k - 1])),
                                16 + d.tempco_exponent - d.exponent);
    }
    EXPECT_LT(sum_abs_q31, std::ldexp(1.0, 31)) << c;
    for (int k = 0; k <= kImuThermalDegree; ++k) {
      const CoeffQ31& coeff = target.thermal[c].drift.coeff[k];
      EXPECT_EQ(target.thermal[c].drift_aligned_q31[k],
                coeff.mantissa_q31 >> (target.thermal[c].drift.work_exponent - coeff.exponent));
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    const CoeffQ31& q = st.accel_quadratic[axis];
    EXPECT_NEAR(std::ldexp(static_cast<double>(st.accel_quadratic_q15[axis]), q.exponent - 15),
                ValueOf(q),
                std::ldexp(1.0, q.exponent - 16));
  }
  for (int r = 0; r < 3; ++r) {
    const int e = st.gs_q15.row_exponent[r];
    int sum_abs = 0;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(std::ldexp(static_cast<double>(st.gs_q15.m_q15[r][c]), e - 15),
                  ValueOf(st.gs[r][c]),
                  std::ldexp(1.0, e - 16));
      sum_abs += std::abs(st.gs_q15.m_q15[r][c]);
    }
    EXPECT_LE(sum_abs, INT16_MAX) << r;
    EXPECT_GT(sum_abs, INT16_MAX / 2) << r;  // the smallest exponent that holds the row
  }
  // The power-on set: F = 1 is delta = 0 at the finest exponent.
  ImuConstants init;
  ImuConstantsInit(&init);
  EXPECT_EQ(init.scale_temperature.delta[0].d0_q31, 0);
  EXPECT_EQ(init.scale_temperature.delta[0].exponent, -16);
}

TEST(ConstantsBlocks, ImuRefusalsLeaveStateUnchanged) {
  ImuConstants c = ExportImuConstants(testing::RealisticImu(6)).constants;
  const ImuConstants before = c;
  int16_t words[kImuMaxBlockWords];
  uint8_t count = 0;
  ImuConstantsReadBlock(&c, kImuBlockGyroCubicFirst, words, kImuMaxBlockWords, &count);
  EXPECT_EQ(ImuConstantsWriteBlock(&c, 0x40, words, count), ConstantsStatus::kUnknownBlock);
  EXPECT_EQ(ImuConstantsWriteBlock(&c, kImuBlockGyroCubicFirst, words, count - 1),
            ConstantsStatus::kWrongLength);
  int16_t bad[kImuMaxBlockWords];
  std::memcpy(bad, words, sizeof(bad));
  bad[2] = 24;  // normalisation shift beyond the gyro count format (23)
  EXPECT_EQ(ImuConstantsWriteBlock(&c, kImuBlockGyroCubicFirst, bad, count),
            ConstantsStatus::kOutOfRange);
  std::memcpy(bad, words, sizeof(bad));
  // l1 (words 7..9 after norm and work exponent) set to 0x7FFF_FFFF at the working exponent:
  // with l0..l3 already using most of +-256 deg/s, the sum of |c| exceeds 2^8.
  bad[3 + 1 + 3] = 0x7FFF;
  bad[3 + 1 + 4] = -1;
  bad[3 + 1 + 5] = kRateExponent;
  EXPECT_EQ(ImuConstantsWriteBlock(&c, kImuBlockGyroCubicFirst, bad, count),
            ConstantsStatus::kWouldOverflow);
  EXPECT_EQ(ImuConstantsWriteBlock(&c, kImuBlockGyroCubicFirst, nullptr, count),
            ConstantsStatus::kNullArgument);
  // A CA row of 30 m/s^2 per g overflows +-256 m/s^2 at the rated 10 g.
  ImuConstantsReadBlock(&c, kImuBlockCa, words, kImuMaxBlockWords, &count);
  words[0] = 0x7800;  // mantissa 0x7800_0000 = 0.9375 at exponent 5: 30
  words[1] = 0;
  words[2] = 5;
  EXPECT_EQ(ImuConstantsWriteBlock(&c, kImuBlockCa, words, count), ConstantsStatus::kWouldOverflow);
  // Accelerometer block: a later channel's bad exponent refuses the whole block.
  ImuConstantsReadBlock(&c, kImuBlockAccelOffsetScale, words, kImuMaxBlockWords, &count);
  words[5 * 5 + 4] = 41;
  EXPECT_EQ(ImuConstantsWriteBlock(&c, kImuBlockAccelOffsetScale, words, count),
            ConstantsStatus::kOutOfRange);
  EXPECT_EQ(std::memcmp(&c, &before, sizeof(c)), 0);
  // Reading into too small a buffer writes nothing.
  EXPECT_EQ(ImuConstantsReadBlock(&c, kImuBlockCa, words, 10, &count),
            ConstantsStatus::kWrongLength);
}

TEST(ConstantsBlocks, AdsRoundTripAndRefusals) {
  const AdsConstants source = ExportAdsConstants(testing::RealisticAds()).constants;
  AdsConstants target;
  AdsConstantsInit(&target);
  const AdsConstants before = target;
  int16_t words[kAdsMaxBlockWords];
  uint8_t count = 0;
  ASSERT_EQ(AdsConstantsReadBlock(&source, kAdsBlockAltitude, words, kAdsMaxBlockWords, &count),
            ConstantsStatus::kOk);
  // 2 x 3 normalisation, 5 exponents, 24 x 3 coefficient, 15 hysteresis, 4 linearisation, law
  EXPECT_EQ(count, 103);
  EXPECT_EQ(words[kAdsSurfaceBlockWords - 1], kAdsLawDirect);
  int16_t bad[kAdsMaxBlockWords];
  std::memcpy(bad, words, sizeof(bad));
  bad[6] = static_cast<int16_t>(bad[6] - 3);  // outer exponent below the b_k bound
  const ConstantsStatus refused = AdsConstantsWriteBlock(&target, kAdsBlockAltitude, bad, count);
  EXPECT_TRUE(refused == ConstantsStatus::kWouldOverflow ||
              refused == ConstantsStatus::kOutOfRange);
  EXPECT_EQ(AdsConstantsWriteBlock(&target, 0x01, words, count), ConstantsStatus::kUnknownBlock);
  EXPECT_EQ(std::memcmp(&target, &before, sizeof(target)), 0);
  ASSERT_EQ(AdsConstantsWriteBlock(&target, kAdsBlockAltitude, words, count), ConstantsStatus::kOk);
  int16_t back[kAdsMaxBlockWords];
  AdsConstantsReadBlock(&target, kAdsBlockAltitude, back, kAdsMaxBlockWords, &count);
  EXPECT_EQ(std::memcmp(words, back, count * sizeof(int16_t)), 0);
}

// The law word: the altitude block takes direct or ISA, the airspeed block direct or CAS; any
// other value changes nothing. A pressure surface's result must fit the pressure format instead
// of the output's, so the same surface words validate under one law and not necessarily another.
TEST(ConstantsBlocks, AdsLawWordIsCheckedPerBlock) {
  const AdsConstants source = ExportAdsConstants(testing::RealisticPressureAds()).constants;
  EXPECT_EQ(source.altitude.law, kAdsLawIsaAltitude);
  EXPECT_EQ(source.airspeed.law, kAdsLawCas);
  AdsConstants target;
  AdsConstantsInit(&target);
  const AdsConstants before = target;
  int16_t words[kAdsMaxBlockWords];
  uint8_t count = 0;
  AdsConstantsReadBlock(&source, kAdsBlockAltitude, words, kAdsMaxBlockWords, &count);
  EXPECT_EQ(words[kAdsSurfaceBlockWords - 1], kAdsLawIsaAltitude);
  for (int16_t law : {int16_t{kAdsLawCas}, int16_t{3}, int16_t{-1}}) {
    words[kAdsSurfaceBlockWords - 1] = law;
    EXPECT_EQ(AdsConstantsWriteBlock(&target, kAdsBlockAltitude, words, count),
              ConstantsStatus::kOutOfRange)
        << law;
  }
  AdsConstantsReadBlock(&source, kAdsBlockAirspeed, words, kAdsMaxBlockWords, &count);
  EXPECT_EQ(words[kAdsSurfaceBlockWords - 1], kAdsLawCas);
  words[kAdsSurfaceBlockWords - 1] = kAdsLawIsaAltitude;
  EXPECT_EQ(AdsConstantsWriteBlock(&target, kAdsBlockAirspeed, words, count),
            ConstantsStatus::kOutOfRange);
  EXPECT_EQ(std::memcmp(&target, &before, sizeof(target)), 0);
  words[kAdsSurfaceBlockWords - 1] = kAdsLawCas;
  EXPECT_EQ(AdsConstantsWriteBlock(&target, kAdsBlockAirspeed, words, count), ConstantsStatus::kOk);
  EXPECT_EQ(target.airspeed.law, kAdsLawCas);
}

// The hysteresis words (ads_constants.h), just before the linearisation's: pressure [inv_span
// (CoeffQ31: mantissa high, low, exponent)][gain (GainQ15: at the centre, per tau, exponent)],
// thermal [t1 t2 t3][inv_span][gain]. Written by the exporter from RealisticPressureAds's terms;
// each refused field changes nothing.
TEST(ConstantsBlocks, AdsHysteresisWordsRoundTripAndRefusals) {
  const AdsCalibrationConstants cal = testing::RealisticPressureAds();
  const AdsConstants source = ExportAdsConstants(cal).constants;
  int16_t words[kAdsMaxBlockWords];
  uint8_t count = 0;
  ASSERT_EQ(AdsConstantsReadBlock(&source, kAdsBlockAltitude, words, kAdsMaxBlockWords, &count),
            ConstantsStatus::kOk);
  constexpr int kAt = kAdsSurfaceBlockWords - 1 - kBridgeLinearisationWords - kAdsHysteresisWords;
  constexpr int kThermal = kAt + kCoeffWords + kGainWords;
  auto coeff = [&](int at) {
    const int32_t mantissa = JoinWords(words[at], static_cast<uint16_t>(words[at + 1]));
    return std::ldexp(static_cast<double>(mantissa), words[at + 2] - 31);
  };
  const HysteresisCompensation& h = cal.altitude_ft.hysteresis;
  // The die temperature at the y normalisation's centre (the gains are given there) and K, the
  // degC of one unit of tau, from t1 (the bridge code is linear in temperature here).
  const double c_per_y = std::ldexp(h.die_temp_c[1], source.altitude.y_norm.shift);
  const double centre_c =
      h.die_temp_c[0] + h.die_temp_c[1] * (source.altitude.y_norm.centre - h.die_temp_origin_code);
  const double k_c = c_per_y / (words[kThermal] / 32768.0);
  auto gain = [&](int at, double tau) {
    return std::ldexp(words[at] + words[at + 1] * tau, words[at + 2] - 15);
  };
  // Values as the exporter was given them, to the words' resolution, at two temperatures.
  EXPECT_NEAR(coeff(kAt), 1.0 / h.pressure_span, 1e-9 / h.pressure_span);
  EXPECT_EQ(words[kAt + 5], 7);  // |at centre| + |per tau| < 128 Pa: within 16 of the result's 17
  for (const double temp_c : {-40.0, 85.0}) {
    const double tau = (temp_c - centre_c) / k_c;
    EXPECT_NEAR(gain(kAt + 3, tau),
                h.pressure_gain + h.pressure_gain_per_c * (temp_c - 25.0),
                2 * 64.0 / 32768.0)
        << temp_c;
    EXPECT_NEAR(gain(kThermal + 6, tau),
                h.thermal_gain + h.thermal_gain_per_c * (temp_c - 25.0),
                2 * 128.0 / 32768.0)
        << temp_c;
  }
  // tau = t1 y: t1 = (degC per normalised y) / K, and inv_span = K / 20 degC, so t1 * inv_span is
  // the travel per unit of normalised y whatever K the exporter chose.
  EXPECT_NEAR(words[kThermal] / 32768.0 * coeff(kThermal + 3),
              c_per_y / h.thermal_span_c,
              1e-4 * c_per_y / h.thermal_span_c);
  EXPECT_EQ(words[kThermal + 1], 0);
  EXPECT_EQ(words[kThermal + 2], 0);

  AdsConstants target;
  AdsConstantsInit(&target);
  const AdsConstants before = target;
  auto refused = [&](std::initializer_list<std::pair<int, int16_t>> changes) {
    int16_t bad[kAdsMaxBlockWords];
    std::memcpy(bad, words, sizeof(bad));
    for (const auto& [at, value] : changes) bad[at] = value;
    return AdsConstantsWriteBlock(&target, kAdsBlockAltitude, bad, count);
  };
  // inv_span mantissa INT32_MIN (no magnitude in Q31).
  EXPECT_EQ(refused({{kAt, INT16_MIN}, {kAt + 1, 0}}), ConstantsStatus::kOutOfRange);
  // Travel shift outside -31..31: pressure input at 2^17 with inv_span at 2^15; tau at 2^0
  // with inv_span at 2^32.
  EXPECT_EQ(refused({{kAt + 2, 15}}), ConstantsStatus::kOutOfRange);
  EXPECT_EQ(refused({{kThermal + 5, 32}}), ConstantsStatus::kOutOfRange);
  // A gain above the result's exponent, or more than 16 below it.
  EXPECT_EQ(refused({{kAt + 5, kPressureExponent + 1}}), ConstantsStatus::kOutOfRange);
  EXPECT_EQ(refused({{kThermal + 8, kPressureExponent - 17}}), ConstantsStatus::kOutOfRange);
  // tau's coefficients summing beyond Q15.
  EXPECT_EQ(refused({{kThermal, 20000}, {kThermal + 1, 13000}}), ConstantsStatus::kWouldOverflow);
  EXPECT_EQ(std::memcmp(&target, &before, sizeof(target)), 0);
  ASSERT_EQ(AdsConstantsWriteBlock(&target, kAdsBlockAltitude, words, count), ConstantsStatus::kOk);
  EXPECT_EQ(target.altitude.pressure.gain.at_centre_q15,
            source.altitude.pressure.gain.at_centre_q15);
  EXPECT_EQ(target.altitude.thermal.gain.per_tau_q15, source.altitude.thermal.gain.per_tau_q15);
  EXPECT_EQ(target.altitude.die_temp_q15[0], source.altitude.die_temp_q15[0]);
  EXPECT_EQ(target.altitude.thermal.inv_span.exponent, source.altitude.thermal.inv_span.exponent);
}

TEST(CalibrationConstants, AdsLawInJsonAndFilesWithoutItAreDirect) {
  AdsCalibrationConstants ads = testing::RealisticAds();
  ads.altitude_ft.law = SurfaceLaw::kIsaAltitude;
  nlohmann::json j = ToJson(ads);
  EXPECT_EQ(j["altitude_ft"]["law"], "isa_altitude");
  EXPECT_EQ(j["airspeed_kt"]["law"], "direct");
  EXPECT_EQ(ToJson(AdsCalibrationConstantsFromJson(j)), j);
  j["altitude_ft"].erase("law");
  EXPECT_EQ(AdsCalibrationConstantsFromJson(j).altitude_ft.law, SurfaceLaw::kDirect);
  j["airspeed_kt"]["law"] = "isa_altitude";
  try {
    AdsCalibrationConstantsFromJson(j);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(std::string(e.what()),
                ::testing::HasSubstr("ads.airspeed_kt.law: expected \"direct\" or \"cas\""));
  }
}

TEST(ConstantsExporter, RefusesUnrepresentableSetsWithReason) {
  ImuCalibrationConstants imu = testing::RealisticImu(7);
  imu.gyro[1].l[1] = 1e-3;  // 1e-3 deg/s per count: +-4.2e6 counts would be +-4,200 deg/s
  try {
    ExportImuConstants(imu);
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("gyro block 0x0C"));
  }
  imu = testing::RealisticImu(7);
  imu.cg[2][0] = 5.0;
  try {
    ExportImuConstants(imu);
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("CG block 0x0F: row 2"));
  }
}

// The bridge code's linearisation: the target holds a whole 24-bit origin and |k| < 4 (k = kappa
// times the power-of-two half-width of the codes behind the y box), and needs the box on the
// root's own branch; anything else is refused naming the block.
TEST(ConstantsExporter, RefusesALinearisationTheTargetCannotHold) {
  const AdsCalibrationConstants good = testing::RealisticPressureAds();
  const AdsConstants exported = ExportAdsConstants(good).constants;
  EXPECT_EQ(exported.altitude.y_linearisation.raw_norm.centre, 6710886);
  EXPECT_NE(exported.altitude.y_linearisation.curvature_q13, 0);
  auto refusal = [](const AdsCalibrationConstants& c) -> std::string {
    try {
      ExportAdsConstants(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  AdsCalibrationConstants bad = good;
  bad.altitude_ft.y_linearisation.origin_code += 0.5;
  EXPECT_THAT(refusal(bad), ::testing::HasSubstr("altitude block 0x21: linearisation origin"));
  bad = good;
  bad.airspeed_kt.y_linearisation.curvature_per_code = 4.0 / (1 << 21);  // k = 4 at shift 21
  EXPECT_THAT(refusal(bad), ::testing::HasSubstr("airspeed block 0x22: bridge curvature"));
  bad = good;
  bad.altitude_ft.y_linearisation.curvature_per_code =
      -2.5 / (bad.altitude_ft.y_max_code - 6710886.0);
  EXPECT_THAT(refusal(bad), ::testing::HasSubstr("turns inside the y box"));
}

TEST(CalibrationConstants, JsonRoundTripAndPathInErrors) {
  const ImuCalibrationConstants imu = testing::RealisticImu(8);
  const ImuCalibrationConstants back = ImuCalibrationConstantsFromJson(ToJson(imu));
  EXPECT_EQ(ToJson(back), ToJson(imu));
  const AdsCalibrationConstants ads = testing::RealisticAds();
  EXPECT_EQ(ToJson(AdsCalibrationConstantsFromJson(ToJson(ads))), ToJson(ads));
  nlohmann::json j = ToJson(imu);
  j["gyro"][2].erase("null_cnt");
  try {
    ImuCalibrationConstantsFromJson(j);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("imu.gyro[2].null_cnt: missing"));
  }
}

}  // namespace
}  // namespace adahrs::firmware_model
