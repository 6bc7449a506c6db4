// The firmware floor of IMU constants (EvaluateImuFirmwareFloor, imu_evaluation.h: the true unit
// projected onto the firmware's model and run through the target compensator over -40...+85 degC,
// six orientations and +-150 deg/s) taken apart effect by effect on eight truth-profile units
// (seeds 7001...7008, the first units of ImuFormat3Fit). Each effect that the truth profile adds
// to the nominal one and that the evaluation's steady-state grid at 5 V can show is switched on
// alone, the others nominal; then every effect together; and the nominal profile without the gyro
// ADCs' quantisation (rate and TEMP), which is what sets the nominal floor. Each set is projected
// onto constants format 2 (no scale-factor terms in temperature) and format 3
// (firmware-compensator.md "Scale-temperature stages").
// Checks, per unit: with format 2 the scale factors' temperature dependence alone makes most of
// the floor (gyro: body rate; accelerometer: acceleration); format 3 removes nearly all of it, and
// its all-effects floor stays below 0.5 mg and 0.05 deg/s. Prints the table that
// docs/calibration-strategies.md "The firmware floor, effect by effect" quotes.
// Not switched singly: the noise terms, rate random walk and die lag (the evaluation switches
// them off) and the supply sensitivities (the grid runs at the nominal 5 V: no effect).
#include <algorithm>
#include <array>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/gravity.h"
#include "proving/evaluation/imu_evaluation.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {
namespace {

using sensor_sim::ImuUnitParams;
using sensor_sim::ModelProfile;

const double kGLocal_mps2 = common::NormalGravityMps2(32.6, 200.0);
constexpr int kUnits = 8;

using Change = std::function<void(ImuUnitParams*)>;

struct Effect {
  std::string name;
  Change switch_on;
};

constexpr const char* kNominal = "none (nominal profile)";
constexpr const char* kUnquantised = "none, gyro ADC quantisation off";
constexpr const char* kAccelScale = "accelerometer scale vs temperature";
constexpr const char* kAccelNonlinearity = "accelerometer nonlinearity";
constexpr const char* kGyroScale = "gyro scale vs temperature";
constexpr const char* kGyroG = "gyro g-sensitivity";
constexpr const char* kAll = "all (truth profile)";

// The truth profile's effects beyond the nominal ones that a steady-state grid at 5 V shows.
std::vector<Effect> SingleEffects() {
  using P = ImuUnitParams;
  return {
      {kAccelScale,
       [](P* p) {
         for (auto& c : p->accel_chips) c.effects.sensitivity_tempco = true;
       }},
      {kAccelNonlinearity,
       [](P* p) {
         for (auto& c : p->accel_chips) c.effects.nonlinearity = true;
       }},
      {"accelerometer T2 vs temperature",
       [](P* p) {
         for (auto& c : p->accel_chips) c.effects.t2_tempco = true;
       }},
      {"accelerometer T2 jitter",
       [](P* p) {
         for (auto& c : p->accel_chips) c.effects.t2_jitter = true;
       }},
      {kGyroScale,
       [](P* p) {
         for (auto& g : p->gyros) g.effects.sensitivity_tempco = true;
       }},
      {kGyroG,
       [](P* p) {
         for (auto& g : p->gyros) g.effects.g_sensitivity = true;
       }},
      {"die self-heating",
       [](P* p) {
         for (auto& t : p->accel_thermal) t.effects.self_heating = true;
         for (auto& t : p->gyro_thermal) t.effects.self_heating = true;
       }},
  };
}

// floors[format][unit]; format 0: constants format 2, 1: format 3.
using Floors = std::array<std::vector<ImuFirmwareFloor>, 2>;

struct Row {
  std::string name;
  Floors floors;
};

Floors FloorsOf(const std::vector<ImuUnitParams>& units) {
  ImuEvaluationOptions options;
  options.g_local_mps2 = kGLocal_mps2;
  options.frames = 40;  // the T2 jitter dithers the capture quantisation; 40 frames average it
  Floors f;
  for (const ImuUnitParams& unit : units) {
    for (int format = 0; format < 2; ++format) {
      f[format].push_back(EvaluateImuFirmwareFloor(unit, format == 1, options));
    }
  }
  return f;
}

// Rows: nominal, nominal unquantised, each single effect over the nominal profile, all effects.
std::vector<Row> Decompose(const std::vector<ImuUnitParams>& truth) {
  std::vector<Row> rows;
  auto add = [&](const std::string& name, const Change& change) {
    std::vector<ImuUnitParams> units = truth;
    for (ImuUnitParams& u : units) change(&u);
    rows.push_back({name, FloorsOf(units)});
  };
  auto nominal_and = [](const Change& on) {
    return [on](ImuUnitParams* p) {
      p->ApplyProfile(ModelProfile::kNominal);
      on(p);
    };
  };
  add(kNominal, nominal_and([](ImuUnitParams*) {}));
  add(kUnquantised, nominal_and([](ImuUnitParams* p) {
        for (auto& g : p->gyros) g.effects.adc_quantization = false;
      }));
  for (const Effect& e : SingleEffects()) add(e.name, nominal_and(e.switch_on));
  add(kAll, [](ImuUnitParams*) {});
  return rows;
}

std::string Range(const std::vector<ImuFirmwareFloor>& v,
                  double ImuFirmwareFloor::*field,
                  int digits) {
  double lo = v[0].*field, hi = v[0].*field;
  for (const ImuFirmwareFloor& f : v) {
    lo = std::min(lo, f.*field);
    hi = std::max(hi, f.*field);
  }
  char lo_text[32], hi_text[32];
  std::snprintf(lo_text, sizeof lo_text, "%.*f", digits, lo);
  std::snprintf(hi_text, sizeof hi_text, "%.*f", digits, hi);
  return std::string(lo_text) + "–" + hi_text;
}

void PrintTable(const std::vector<Row>& rows) {
  std::printf(
      "| effect switched on | acceleration, format 2 | format 3 | body rate, format 2 | format 3 "
      "|\n");
  std::printf("|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %s mg | %s mg | %s °/s | %s °/s |\n",
                r.name.c_str(),
                Range(r.floors[0], &ImuFirmwareFloor::worst_accel_mg, 2).c_str(),
                Range(r.floors[1], &ImuFirmwareFloor::worst_accel_mg, 2).c_str(),
                Range(r.floors[0], &ImuFirmwareFloor::worst_rate_dps, 3).c_str(),
                Range(r.floors[1], &ImuFirmwareFloor::worst_rate_dps, 3).c_str());
  }
}

void PrintUnit(const std::vector<Row>& rows, const std::string& serial, int u) {
  for (const Row& r : rows) {
    std::printf("%s %-36s format 2: %6.3f mg %6.4f deg/s; format 3: %6.3f mg %6.4f deg/s\n",
                serial.c_str(),
                r.name.c_str(),
                r.floors[0][u].worst_accel_mg,
                r.floors[0][u].worst_rate_dps,
                r.floors[1][u].worst_accel_mg,
                r.floors[1][u].worst_rate_dps);
  }
}

const Floors& FloorsNamed(const std::vector<Row>& rows, const std::string& name) {
  const auto it =
      std::find_if(rows.begin(), rows.end(), [&](const Row& r) { return r.name == name; });
  if (it == rows.end()) throw std::logic_error("no row " + name);
  return it->floors;
}

TEST(ImuFloorDecomposition, ScaleFactorsInTemperatureMakeTheFormat2FloorAndFormat3RemovesIt) {
  std::vector<ImuUnitParams> truth;
  for (int n = 1; n <= kUnits; ++n) {
    truth.push_back(
        ImuUnitParams::Draw("IMU-000" + std::to_string(n), 7000 + n, ModelProfile::kTruth));
  }
  const std::vector<Row> rows = Decompose(truth);
  PrintTable(rows);
  const Floors& all = FloorsNamed(rows, kAll);
  const Floors& nominal = FloorsNamed(rows, kNominal);
  const Floors& unquantised = FloorsNamed(rows, kUnquantised);
  const Floors& accel_scale = FloorsNamed(rows, kAccelScale);
  const Floors& gyro_scale = FloorsNamed(rows, kGyroScale);
  const Floors& gyro_g = FloorsNamed(rows, kGyroG);
  const Floors& accel_nonlinearity = FloorsNamed(rows, kAccelNonlinearity);
  for (int u = 0; u < kUnits; ++u) {
    SCOPED_TRACE(truth[u].serial);
    PrintUnit(rows, truth[u].serial, u);
    const ImuFirmwareFloor all2 = all[0][u], all3 = all[1][u];
    // Format 2: the drawn tempcos (3 sigma 240 ppm/degC accelerometer, 500 ppm/degC gyro) leave
    // milli-g and deg/s; each scale tempco alone is most of its quantity's floor. Worst errors do
    // not add (they sit at different grid points), so a single effect can exceed the total;
    // measured 0.93...1.10 of it on these units and 20 units, asserted above 0.85.
    EXPECT_GT(all2.worst_accel_mg, 2.0);
    EXPECT_GT(all2.worst_rate_dps, 1.0);
    EXPECT_GE(accel_scale[0][u].worst_accel_mg, 0.85 * all2.worst_accel_mg);
    EXPECT_GE(gyro_scale[0][u].worst_rate_dps, 0.85 * all2.worst_rate_dps);
    // The other format-3 effects under format 2: tenths of a milli-g and of a deg/s (measured
    // 0.14...0.70 mg and 0.08...0.22 deg/s on 20 units).
    EXPECT_LT(accel_nonlinearity[0][u].worst_accel_mg, 1.0);
    EXPECT_GT(gyro_g[0][u].worst_rate_dps, 0.05);
    EXPECT_LT(gyro_g[0][u].worst_rate_dps, 0.3);
    // Format 3 holds them: the scale tempcos' floors fall to a few per cent of format 2's
    // (measured at most 5.5 % accelerometer, 1.4 % gyro on 20 units), g-sensitivity and
    // nonlinearity to the nominal floor.
    EXPECT_LT(accel_scale[1][u].worst_accel_mg, 0.1 * accel_scale[0][u].worst_accel_mg);
    EXPECT_LT(gyro_scale[1][u].worst_rate_dps, 0.03 * gyro_scale[0][u].worst_rate_dps);
    EXPECT_LT(accel_nonlinearity[1][u].worst_accel_mg, nominal[1][u].worst_accel_mg + 0.1);
    EXPECT_LT(gyro_g[1][u].worst_rate_dps, nominal[1][u].worst_rate_dps + 0.002);
    // The format-3 floor with every effect: half the 1.0 mg specification, and below the 0.06 deg/s
    // the design's CRB limit allows at best (measured 0.14...0.25 mg and 0.009...0.036 deg/s).
    EXPECT_LT(all3.worst_accel_mg, 0.5);
    EXPECT_LT(all3.worst_rate_dps, 0.05);
    // The nominal floor is mostly the gyro ADCs' quantisation (the TEMP reading steps 0.14 degC
    // on a noise-free grid) times the zero-g and null drift: without it the rate floor falls
    // from 0.003...0.009 to below 0.001 deg/s, the acceleration floor from 0.10...0.22 to
    // 0.03...0.11 mg.
    EXPECT_LT(unquantised[0][u].worst_accel_mg, nominal[0][u].worst_accel_mg);
    EXPECT_LT(unquantised[0][u].worst_rate_dps, 0.002);
  }
}

}  // namespace
}  // namespace adahrs::proving
