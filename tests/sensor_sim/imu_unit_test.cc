#include "sensor_sim/imu_unit.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/imu_layout.h"
#include "common/units.h"

namespace adahrs::sensor_sim {
namespace {

constexpr int kFrames = 4000;

// Mean duty T1/T2 of every accelerometer channel and mean gyro counts over `frames` frames.
struct Means {
  std::array<double, 6> duty{};
  std::array<double, 3> gyro_cnt{};
  std::array<double, 3> temp_cnt{};
};

Means Average(ImuUnit& unit, const ImuStimulus& s, int frames) {
  Means m;
  for (int i = 0; i < frames; ++i) {
    const ImuRawFrame f = unit.Step(s);
    for (int ch = 0; ch < 6; ++ch) m.duty[ch] += double(f.accel[ch].t1_cnt) / f.accel[ch].t2_cnt;
    for (int g = 0; g < 3; ++g) {
      m.gyro_cnt[g] += f.gyro_cnt[g];
      m.temp_cnt[g] += f.temp_cnt[g];
    }
  }
  for (double& d : m.duty) d /= frames;
  for (double& c : m.gyro_cnt) c /= frames;
  for (double& c : m.temp_cnt) c /= frames;
  return m;
}

ImuUnitParams QuietUnit(uint64_t seed) {
  // Drawn unit, nominal profile, thermal lag and self-heating off so the dies sit at the air.
  ImuUnitParams p = ImuUnitParams::Draw("IMU-T", seed, ModelProfile::kNominal);
  for (auto& t : p.accel_thermal) t.effects = DieThermalEffects::Nominal();
  for (auto& t : p.gyro_thermal) t.effects = DieThermalEffects::Nominal();
  return p;
}

ImuStimulus AtRest(const Eigen::Vector3d& up_B) {
  ImuStimulus s;
  s.f_B_g = up_B;
  return s;
}

// A six-position pair (axis up, axis down) isolates each channel's response to the body axis:
// (D_up − D_down)/2 = S · (R_CB row · axis). The expected value comes from the drawn truth (chip
// sensitivity and mounting), the signs from the reference scale factors (az1 −, ax1 −, ay1 +,
// az2 +, ax2 +, ay2 −).
TEST(ImuUnit, SixPositionPairsSeeEachChannelsAxisWithTheReferenceSigns) {
  const ImuUnitParams p = QuietUnit(21);
  const std::array<int, 6> channel_axis = {2, 0, 1, 2, 0, 1};
  const std::array<double, 6> reference_sign = {-1, -1, +1, +1, +1, -1};
  for (int ch = 0; ch < 6; ++ch) {
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(channel_axis[ch]);
    ImuUnit up(p, 5, 25.0), down(p, 6, 25.0);
    const double half_diff = (Average(up, AtRest(axis), kFrames).duty[ch] -
                              Average(down, AtRest(-axis), kFrames).duty[ch]) /
                             2;
    const common::ImuChannel& ca = common::kImuChannels[ch];
    const Adxl210eAxisParams& ap =
        ca.package_axis == 0 ? p.accel_chips[ca.package].x : p.accel_chips[ca.package].y;
    const double expected = ap.sensitivity_pct_per_g / 100.0 *
                            p.geometry.R_CB(ca.package)(ca.package_axis, channel_axis[ch]);
    EXPECT_EQ(std::signbit(half_diff), reference_sign[ch] < 0) << common::kAccelChannelNames[ch];
    // 1.8 mg rms per frame, averaged over 4000 correlated frames, plus cross-axis terms of the
    // chip (≤ 2 % of the 1 g on the other axes is zero here: the other axes see 0 g): 1 % covers
    // it.
    EXPECT_NEAR(half_diff, expected, 0.01 * std::abs(expected)) << common::kAccelChannelNames[ch];
  }
}

TEST(ImuUnit, TableRateReachesEachGyroThroughItsMounting) {
  const ImuUnitParams p = QuietUnit(22);
  for (int g = 0; g < 3; ++g) {
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(g);
    ImuStimulus spinning = AtRest(axis), still = AtRest(axis);
    spinning.w_B_dps = 100.0 * axis;
    ImuUnit a(p, 7, 25.0), b(p, 7, 25.0);
    const double diff =
        Average(a, spinning, kFrames).gyro_cnt[g] - Average(b, still, kFrames).gyro_cnt[g];
    const Adxrs150 gyro(p.gyros[g], 1, p.frame_period_s);
    const double expected = 100.0 * gyro.RateCountsPerDps() * p.geometry.R_GB(g)(2, g);
    // Same noise seed in both runs cancels white noise; the 0.1 % FS nonlinearity at 100 °/s is
    // below 0.15 °/s of 100: 0.2 % covers it.
    EXPECT_NEAR(diff, expected, 0.002 * expected) << common::kGyroChannelNames[g];
  }
}

TEST(ImuUnit, TemperatureCountsFollowTheGyroDiesWithTheirLag) {
  ImuUnitParams p = ImuUnitParams::Draw("IMU-T", 23, ModelProfile::kTruth);
  ImuUnit unit(p, 1, 25.0);
  ImuStimulus s = AtRest(Eigen::Vector3d::UnitZ());
  s.air_temp_c = 45.0;
  for (int i = 0; i < 100; ++i) unit.Step(s);  // one second after a 20 °C air step
  for (int g = 0; g < 3; ++g) {
    const double expected_c =
        45.0 + p.gyro_thermal[g].self_heating_c -
        (20.0 + p.gyro_thermal[g].self_heating_c) * std::exp(-1.0 / p.gyro_thermal[g].tau_s);
    EXPECT_NEAR(unit.die_temperatures().gyro_c[g], expected_c, 1e-6);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(unit.die_temperatures().accel_chip_c[k], 30.0);  // minutes of lag, not seconds
  }
}

TEST(ImuUnit, DeterministicPerSeedAndDifferentAcrossSeeds) {
  const ImuUnitParams p = ImuUnitParams::Draw("IMU-T", 24, ModelProfile::kTruth);
  ImuUnit a(p, 1, 20.0), b(p, 1, 20.0), c(p, 2, 20.0);
  const ImuStimulus s = AtRest(Eigen::Vector3d::UnitX());
  bool any_difference = false;
  for (int i = 0; i < 200; ++i) {
    const ImuRawFrame fa = a.Step(s), fb = b.Step(s), fc = c.Step(s);
    EXPECT_EQ(fa.gyro_cnt, fb.gyro_cnt);
    EXPECT_EQ(fa.temp_cnt, fb.temp_cnt);
    for (int ch = 0; ch < 6; ++ch) EXPECT_EQ(fa.accel[ch].t1_cnt, fb.accel[ch].t1_cnt);
    any_difference |= fa.gyro_cnt != fc.gyro_cnt;
  }
  EXPECT_TRUE(any_difference);
}

TEST(ImuUnit, ProfilesDifferOnlyByEffects) {
  nlohmann::json nominal = ImuUnitParams::Draw("IMU-T", 25, ModelProfile::kNominal).ToJson();
  nlohmann::json truth = ImuUnitParams::Draw("IMU-T", 25, ModelProfile::kTruth).ToJson();
  EXPECT_NE(nominal, truth);
  const auto strip = [](nlohmann::json& j) {
    for (const char* key : {"accel_chips", "gyros", "accel_thermal", "gyro_thermal"}) {
      for (auto& item : j[key]) item.erase("effects");
    }
  };
  strip(nominal);
  strip(truth);
  EXPECT_EQ(nominal, truth);
}

TEST(ImuUnit, TruthJsonRoundTripsExactly) {
  const ImuUnitParams p = ImuUnitParams::Draw("IMU-0042", 26, ModelProfile::kTruth);
  const nlohmann::json j = nlohmann::json::parse(p.ToJson().dump());
  const ImuUnitParams q = ImuUnitParams::FromJson(common::ParamReader(j, "truth.json"));
  EXPECT_EQ(q.ToJson(), p.ToJson());
  EXPECT_EQ(q.serial, "IMU-0042");
}

TEST(ImuUnit, BadTruthFileNamesTheNestedPath) {
  nlohmann::json j = ImuUnitParams::Draw("IMU-1", 27, ModelProfile::kTruth).ToJson();
  j["gyro_thermal"][2]["tau_s"] = "NaN";
  try {
    ImuUnitParams::FromJson(common::ParamReader(j, "truth.json"));
    FAIL();
  } catch (const common::ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("truth.json: $.gyro_thermal[2].tau_s"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
