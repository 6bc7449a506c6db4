// Diagnosis proofs (docs/diagnose.md): simulated units whose truth has one effect more than the
// pipeline's model, the effect concealed, must be found, named and sized within the stated
// uncertainty; clean units must give no finding. The scenario generator (imu_diagnosis_scenario.h)
// is the simulator; the diagnoser (diagnosis/) never includes it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/imu_layout.h"
#include "diagnosis/diagnosis_cells.h"
#include "diagnosis/imu_diagnosis.h"
#include "proving/demo/diagnosis_truth.h"
#include "sensor_sim/im3_geometry.h"
#include "sensor_sim/imu_unit.h"
#include "tests/diagnosis/imu_diagnosis_scenario.h"
#include "tests/support/sanitized_units.h"
#include "tests/support/statistical_gates.h"

namespace adahrs::diagnosis {
namespace {

using sensor_sim::ImuUnitParams;
using sensor_sim::ModelProfile;
using testing::ImuScenario;

// A drawn unit with the nominal profile (what the pipeline's model expresses).
ImuUnitParams Nominal(uint64_t seed) {
  return ImuUnitParams::Draw("IMU-0001", seed, ModelProfile::kNominal);
}

struct Shape {
  std::vector<double> profile_c = {-20.0, 70.0, 25.0};
  double ramp_c_per_min = 10.0;
  double soak_s = 300.0;
  std::vector<double> sensor_cal_c = {25.0};
  double settle_s = 1.0;  // unrecorded soak before each sensor calibration
  int accel_packets = 500;
  int gyro_packets = 300;
};

// `write`, when given, sets effects the scenario writes onto the counts before the run.
calib::ImuUnitData Simulate(const ImuUnitParams& p,
                            uint64_t noise_seed,
                            const Shape& shape,
                            const std::function<void(ImuScenario&)>& write = {}) {
  ImuScenario s(p, noise_seed, 25.0);
  if (write) write(s);
  s.ThermalProfile(31, shape.profile_c, shape.ramp_c_per_min, shape.soak_s);
  int step = 2;
  for (double t : shape.sensor_cal_c) {
    s.Soak(t, shape.settle_s);
    s.SensorCalibration(step, shape.accel_packets, shape.gyro_packets);
    step += 9;
  }
  return s.data();
}

UnitDiagnosis Diagnose(const calib::ImuUnitData& d) {
  return DiagnoseImu(BuildDiagnosisData(d, 9.80665));
}

void Print(const UnitDiagnosis& d) {
  for (const Finding& f : d.findings)
    std::printf("  finding: %s (p %.2g, held-out %.4g -> %.4g %s)\n",
                f.words.c_str(),
                f.wald_p_value,
                f.held_out_rms_before,
                f.held_out_rms_after,
                f.rms_unit.c_str());
  for (const Unexplained& u : d.unexplained)
    std::printf(
        "  unexplained: %s %s: %s\n", u.channel.c_str(), u.where.c_str(), u.description.c_str());
  for (const std::string& n : d.notes) std::printf("  note: %s\n", n.c_str());
  for (const ChannelFitSummary& c : d.channels)
    std::printf("  %s held-out %.4g -> %.4g %s (white %.3g)\n",
                c.channel.c_str(),
                c.held_out_rms_baseline,
                c.held_out_rms_final,
                c.unit.c_str(),
                c.white_noise_rms);
}

// The truth's polynomial c1 dT + c2 dT^2 + c3 dT^3 as the recording sees it: its least-squares
// projection onto (dT, dT^2) over the temperatures visited (a cubic term aliases into the linear
// one when only three temperatures are visited).
std::array<double, 2> Projected(double c1,
                                double c2,
                                double c3,
                                const std::vector<double>& temps_c) {
  Eigen::MatrixXd a(static_cast<int>(temps_c.size()), 3);
  Eigen::VectorXd y(static_cast<int>(temps_c.size()));
  for (size_t i = 0; i < temps_c.size(); ++i) {
    const double d = temps_c[i] - 25.0;
    a.row(static_cast<int>(i)) << 1.0, d, d * d;
    y[static_cast<int>(i)] = c1 * d + c2 * d * d + c3 * d * d * d;
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(y);
  return {x[1], x[2]};
}

const DetectionLimit* Limit(const UnitDiagnosis& d,
                            const std::string& effect,
                            const std::string& channel) {
  for (const DetectionLimit& l : d.detection_limits) {
    if (l.effect == effect && l.channel == channel) return &l;
  }
  return nullptr;
}

// True when some component of the truth exceeds the recording's stated detection limit.
bool Detectable(const DetectionLimit* l, const std::vector<double>& truth) {
  if (l == nullptr || l->limits.size() != truth.size()) return false;
  for (size_t k = 0; k < truth.size(); ++k) {
    if (std::abs(truth[k]) > l->limits[k].magnitude) return true;
  }
  return false;
}

const Finding* Find(const UnitDiagnosis& d, const std::string& effect, const std::string& channel) {
  for (const Finding& f : d.findings) {
    if (f.effect == effect && f.channel == channel) return &f;
  }
  return nullptr;
}

// Counts components within 3 standard errors of the truth (plus a stated model allowance), and
// bounds those standard errors from above by the same components' scatter about the truth
// (tests/support/statistical_gates.h): a test leans on the diagnoser's errors only so bounded.
struct Tally {
  explicit Tally(const std::string& what = "sized", int components_per_finding = 1)
      : bound(what), per_finding(components_per_finding) {}
  int within = 0;
  int total = 0;
  adahrs::testing::StandardErrorBound bound;
  int per_finding;
  void Check(double found, double se, double truth, double allowance = 0.0) {
    ++total;
    if (std::abs(found - truth) <= 3.0 * se + allowance) ++within;
    bound.AddComponent(found, se, truth);
    if (total % per_finding == 0) bound.EndFinding();
  }
  // At least `min_findings` sized; at most the binomial share of honest components beyond 3 SE
  // outside (2.7e-3 each, at the suite's false-failure rate); the errors not inflated.
  void Expect(int min_findings, double documented_inflation = 1.0) const {
    EXPECT_GE(within, adahrs::testing::RequiredWithinThreeSe(total))
        << within << " of " << total << " within";
    bound.Expect(min_findings, documented_inflation);
  }
};

// Clean units (nominal profile, every effect the model expresses). The diagnoser's stated rates
// per clean unit (docs/diagnose.md "Measured", over 1,100 units): a finding on 3 % (the nominal
// level 0.001 is Bonferroni's over the unit's tests, and the jackknife over a few dozen segments
// is anti-conservative), unexplained structure on 1.5 %. Each gate allows the binomial count at
// its rate over these units at the suite's false-failure rate (tests/support/statistical_gates.h):
// 9 and 6 of 100; under the sanitizers 20 seeds (tests/support/sanitized_units.h), 4 and 3.
TEST(ImuDiagnosis, CleanRecordingsGiveNoFindingsOverAHundredSeeds) {
  constexpr double kFindingRatePerUnit = 0.03;
  constexpr double kUnexplainedRatePerUnit = 0.015;
  Shape shape;
  shape.sensor_cal_c = {-20.0, 25.0, 70.0};
  const int units = adahrs::testing::Units(100, 20);
  int with_findings = 0, with_unexplained = 0;
  for (uint64_t seed = 1; seed <= static_cast<uint64_t>(units); ++seed) {
    const UnitDiagnosis d = Diagnose(Simulate(Nominal(seed), 1000 + seed, shape));
    if (!d.findings.empty()) {
      ++with_findings;
      std::printf("seed %d:\n", static_cast<int>(seed));
      Print(d);
    }
    if (!d.unexplained.empty()) ++with_unexplained;
    for (const Unexplained& u : d.unexplained) {
      if (d.findings.empty())
        std::printf("seed %d: unexplained: %s %s: %s\n",
                    static_cast<int>(seed),
                    u.channel.c_str(),
                    u.where.c_str(),
                    u.description.c_str());
    }
  }
  std::printf("clean: %d of %d units with a finding, %d with unexplained structure\n",
              with_findings,
              units,
              with_unexplained);
  EXPECT_LE(with_findings, adahrs::testing::AllowedCount(units, kFindingRatePerUnit));
  EXPECT_LE(with_unexplained, adahrs::testing::AllowedCount(units, kUnexplainedRatePerUnit));
}

// Gyro g-sensitivity looks like an orientation-dependent bias: found on every gyro where the truth
// exceeds the stated detection limit (80 % power: at most 20 % missed), sized within 3 standard
// errors of the truth expressed in B (R_GB' g_G) on all but the binomial share of components,
// those errors bounded by the truth's scatter (Tally).
TEST(ImuDiagnosis, FindsGyroGSensitivityConcealedAsOrientationBias) {
  Shape shape;
  Tally tally("g-sensitivity", 3);
  int detectable = 0, missed = 0, others = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    ImuUnitParams p = Nominal(100 + seed);
    for (auto& g : p.gyros) g.effects.g_sensitivity = true;
    const UnitDiagnosis d = Diagnose(Simulate(p, 2000 + seed, shape));
    for (int g = 0; g < 3; ++g) {
      const Eigen::Vector3d g_G(p.gyros[g].g_sensitivity_dps_per_g.data());
      const Eigen::Vector3d truth_B = p.geometry.R_GB(g).transpose() * g_G;
      const Finding* f = Find(d, "gyro_g_sensitivity", common::kImuChannelNames[6 + g]);
      const bool can = Detectable(Limit(d, "gyro_g_sensitivity", common::kImuChannelNames[6 + g]),
                                  {truth_B[0], truth_B[1], truth_B[2]});
      detectable += can;
      if (f == nullptr) {
        missed += can;
        continue;
      }
      EXPECT_LT(f->held_out_rms_after, f->held_out_rms_before);
      for (int k = 0; k < 3; ++k)
        tally.Check(f->components[k].magnitude, f->components[k].standard_error, truth_B[k]);
    }
    for (const Finding& f : d.findings) {
      if (f.effect != "gyro_g_sensitivity") {
        ++others;
        std::printf("seed %d, not in the truth: %s\n", static_cast<int>(seed), f.words.c_str());
      }
    }
  }
  std::printf("g-sensitivity: %d of %d components within 3 SE; %d of %d detectable gyros missed\n",
              tally.within,
              tally.total,
              missed,
              detectable);
  tally.Expect(18);
  EXPECT_LE(missed, detectable / 5);
  EXPECT_GE(detectable, 18);  // of the 30 drawn gyros, at the family level over 57 tests
  // Measured 2026-11-26: 3 findings not in the truth over these 10 units (die lag, scale tempco
  // on the one-temperature shape), far above the clean shape's rate: docs/diagnose.md, open.
  EXPECT_LE(others, 3);
}

// Scale factor vs temperature is absorbed by a calibration at one temperature; with the six
// positions and rates repeated at -20 and 70 degC it is found on every channel where the truth
// exceeds the detection limit, and sized within 3 standard errors of the truth as projected on
// the visited temperatures.
TEST(ImuDiagnosis, FindsScaleFactorTempcoVisibleOnlyAwayFromTheCalibrationTemperature) {
  Shape shape;
  shape.sensor_cal_c = {-20.0, 25.0, 70.0};
  Tally tally("scale tempco", 2);
  int missed = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    ImuUnitParams p = Nominal(200 + seed);
    for (auto& c : p.accel_chips) c.effects.sensitivity_tempco = true;
    for (auto& g : p.gyros) g.effects.sensitivity_tempco = true;
    const UnitDiagnosis d = Diagnose(Simulate(p, 3000 + seed, shape));
    for (int ch = 0; ch < 9; ++ch) {
      std::array<double, 2> truth;
      if (ch < 6) {
        const auto& axis = ch % 2 == 0 ? p.accel_chips[ch / 2].x : p.accel_chips[ch / 2].y;
        truth = Projected(axis.sensitivity_tc1_ppm_per_c,
                          axis.sensitivity_tc2_ppm_per_c2,
                          axis.sensitivity_tc3_ppm_per_c3,
                          shape.sensor_cal_c);
      } else {
        const auto& g = p.gyros[ch - 6];
        truth = {g.sensitivity_tc1_ppm_per_c, g.sensitivity_tc2_ppm_per_c2};
      }
      const Finding* f = Find(d, "scale_factor_tempco", common::kImuChannelNames[ch]);
      if (f == nullptr) {
        ++missed;
        continue;
      }
      tally.Check(f->components[0].magnitude, f->components[0].standard_error, truth[0]);
      tally.Check(f->components[1].magnitude, f->components[1].standard_error, truth[1]);
    }
  }
  std::printf("scale tempco: %d of %d components within 3 SE, %d channels missed\n",
              tally.within,
              tally.total,
              missed);
  tally.Expect(85);
  EXPECT_LE(missed, 5);
}

TEST(ImuDiagnosis, ScaleFactorTempcoIsUndetectableFromOneCalibrationTemperature) {
  Shape shape;
  ImuUnitParams p = Nominal(301);
  for (auto& g : p.gyros) g.effects.sensitivity_tempco = true;
  const UnitDiagnosis d = Diagnose(Simulate(p, 4001, shape));
  for (const Finding& f : d.findings) ADD_FAILURE() << f.words;
  for (const DetectionLimit& l : d.detection_limits) {
    if (l.effect == "scale_factor_tempco" && l.channel[0] == 'g') {
      // Only the few tenths of a degree the die wanders during the rate steps excite it.
      const double limit = l.limits.empty() ? INFINITY : l.limits[0].magnitude;
      std::printf("%s scale tempco detection limit %g ppm/degC %s\n",
                  l.channel.c_str(),
                  limit,
                  l.note.c_str());
      EXPECT_GT(limit, 1000.0) << l.channel;
    }
  }
}

// Die lag between the accelerometer chips and the gyro dies whose TEMP pins are the thermometers:
// on a monotone ramp it is indistinguishable from a shifted temperature polynomial; the up and
// down ramps of two thermal cycles tell it apart (with one cycle the jackknife has too few
// informative segments: docs/diagnose.md). Sized within 3 SE plus 15 % of the truth (the
// first-order lag term is exact only on a steady ramp). Under the sanitizers 3 units.
TEST(ImuDiagnosis, FindsDieLagConfoundedWithTheTemperaturePolynomial) {
  Shape shape;
  shape.profile_c = {0.0, 50.0, 0.0, 50.0, 25.0};
  shape.ramp_c_per_min = 4.0;
  shape.soak_s = 1500.0;
  Tally tally("die lag");
  int missed = 0, detectable = 0;
  const int units = adahrs::testing::Units(10, 3);
  for (uint64_t seed = 1; seed <= static_cast<uint64_t>(units); ++seed) {
    ImuUnitParams p = Nominal(400 + seed);
    for (auto& t : p.accel_thermal) t.effects.lag = true;
    for (auto& t : p.gyro_thermal) t.effects.lag = true;
    const UnitDiagnosis d = Diagnose(Simulate(p, 5000 + seed, shape));
    for (int ch = 0; ch < 6; ++ch) {
      const double truth = p.accel_thermal[ch / 2].tau_s -
                           p.gyro_thermal[common::kImuChannels[ch].thermometer].tau_s;
      const Finding* f = Find(d, "die_thermal_lag", common::kImuChannelNames[ch]);
      const bool can =
          Detectable(Limit(d, "die_thermal_lag", common::kImuChannelNames[ch]), {truth});
      detectable += can;
      if (f == nullptr) {
        missed += can;
        continue;
      }
      tally.Check(f->components[0].magnitude,
                  f->components[0].standard_error,
                  truth,
                  0.15 * std::abs(truth));
    }
    for (int ch = 6; ch < 9; ++ch)
      EXPECT_EQ(Find(d, "die_thermal_lag", common::kImuChannelNames[ch]), nullptr);
  }
  std::printf("die lag: %d of %d within 3 SE + 15 %%, %d of %d detectable channels missed\n",
              tally.within,
              tally.total,
              missed,
              detectable);
  // docs/diagnose.md: 60 of 60 channels detectable and found. Every channel counts, not only
  // those the diagnoser's own limits call detectable: limits that call a channel undetectable
  // fail here rather than excuse its miss.
  EXPECT_EQ(detectable, 6 * units);
  EXPECT_EQ(missed, 0);
  tally.Expect(6 * units);
}

// A bias step (an effect outside the library) is located and not forced into a term.
TEST(ImuDiagnosis, LocatesABiasStepWithoutFittingAnyTerm) {
  Shape shape;
  calib::ImuUnitData data = Simulate(Nominal(601), 7001, shape);
  const double t_step = data.thermal[data.thermal.size() - 15000].t_s;  // inside the last soak
  for (calib::ImuSample& s : data.thermal) {
    if (s.t_s >= t_step)
      s.raw.t1_cnt[5] = static_cast<uint16_t>(s.raw.t1_cnt[5] + 30);  // ay2: ~1e-3 duty
  }
  const UnitDiagnosis d = Diagnose(data);
  for (const Finding& f : d.findings) ADD_FAILURE() << f.words;
  bool located = false;
  for (const Unexplained& u : d.unexplained) {
    std::printf(
        "unexplained: %s %s: %s\n", u.channel.c_str(), u.where.c_str(), u.description.c_str());
    const size_t at = u.where.find("t = ");
    if (u.channel == "ay2" && at != std::string::npos) {
      EXPECT_NEAR(std::stod(u.where.substr(at + 4)), t_step, 2.0);
      located = true;
    }
  }
  EXPECT_TRUE(located);
}

// The worst segment's stated 90 % step limit of `channel` from the unit's notes, in its unit.
double StatedStepLimit(const UnitDiagnosis& d, const std::string& channel) {
  for (const std::string& n : d.notes) {
    if (n.rfind(channel + ": steps located", 0) != 0) continue;
    const size_t to = n.find(") to ");
    if (to != std::string::npos) return std::stod(n.substr(to + 5));
  }
  return 0.0;
}

// Gyro bias steps halfway up a 2 degC/min ramp (a thermal run's pace), written onto the counts of
// 10 units (each gyro axis in turn): 0.1 deg/s, about 3 times the spread the simulated ADXRS150's
// bias flicker gives a 30 s contrast (bias instability 50-100 deg/h, physics.md), and 0.3 deg/s.
// A step above the unit's stated 90 % limit is located within 60 s of where it was written on at
// least 9 of 10 units; the clean units show no step at all (the rule's design rate, 1e-3 per
// channel-hour, gives 0.2 expected over these 10 units' 180 channel-hours). Under the sanitizers
// 3 units.
TEST(ImuDiagnosis, LocatesGyroBiasStepsAboveTheStatedLimitOnASlowThermalRamp) {
  Shape shape;
  shape.ramp_c_per_min = 2.0;
  int clean_steps = 0;
  std::map<double, std::array<int, 3>> tally;  // size: above limit, located of those, located
  const int units = adahrs::testing::Units(10, 3);
  for (int unit = 0; unit < units; ++unit) {
    const calib::ImuUnitData clean_data = Simulate(Nominal(620 + unit), 7020 + unit, shape);
    const UnitDiagnosis clean = Diagnose(clean_data);
    for (const Unexplained& u : clean.unexplained) {
      if (u.description.find("a step of") == std::string::npos) continue;
      ++clean_steps;
      std::printf("clean unit %d: %s %s: %s\n",
                  unit,
                  u.channel.c_str(),
                  u.where.c_str(),
                  u.description.c_str());
    }
    // Halfway up the -20 -> 70 degC ramp, in the rows' own time.
    double t_step = 0.0;
    for (size_t i = 0; i < clean_data.thermal.size(); ++i) {
      if (clean_data.thermal_segment[i] == calib::ThermalSegment::kUpRamp &&
          clean_data.thermal[i].chamber_c >= 25.0) {
        t_step = clean_data.thermal[i].t_s;
        break;
      }
    }
    const int axis = unit % 3;
    const std::string channel = common::kImuChannelNames[6 + axis];
    for (double size_dps : {0.1, 0.3}) {
      calib::ImuUnitData data = clean_data;
      for (calib::ImuSample& s : data.thermal) {
        if (s.t_s >= t_step)
          s.raw.gyro_cnt[axis] +=
              static_cast<int32_t>(std::lround(size_dps * kGyroDatasheetCountsPerDps));
      }
      const UnitDiagnosis d = Diagnose(data);
      bool located = false;
      for (const Unexplained& u : d.unexplained) {
        const size_t at = u.where.find("t = ");
        if (u.channel == channel && at != std::string::npos &&
            std::abs(std::stod(u.where.substr(at + 4)) - t_step) <= 60.0)
          located = true;
      }
      const double limit_dps = StatedStepLimit(d, channel);
      std::printf("unit %d %s: step %.2f deg/s at t = %.1f s %s; stated limit %.3g deg/s\n",
                  unit,
                  channel.c_str(),
                  size_dps,
                  t_step,
                  located ? "located" : "not located",
                  limit_dps);
      EXPECT_GT(limit_dps, 0.0) << "no step limit stated for " << channel;
      std::array<int, 3>& t = tally[size_dps];
      if (size_dps > limit_dps) {
        ++t[0];
        if (located) ++t[1];
      }
      if (located) ++t[2];
    }
  }
  for (const auto& [size_dps, t] : tally) {
    std::printf(
        "step %.2f deg/s: above the stated limit on %d units, located on %d of those; "
        "located on %d of %d in all\n",
        size_dps,
        t[0],
        t[1],
        t[2],
        units);
    EXPECT_GE(t[1], t[0] - t[0] / 10) << size_dps << " deg/s";
  }
  EXPECT_EQ(tally[0.3][0], units) << "0.3 deg/s should exceed every stated limit";
  EXPECT_EQ(clean_steps, 0);
}

// Packets lost inside a segment are counted by the sequence counter and said, never interpolated.
TEST(ImuDiagnosis, ReportsPacketsMissingByTheSequenceCounter) {
  Shape shape;
  calib::ImuUnitData data = Simulate(Nominal(602), 7002, shape);
  const auto has_note = [](const UnitDiagnosis& d, const std::string& text) {
    return std::any_of(d.notes.begin(), d.notes.end(), [&](const std::string& n) {
      return n.find(text) != std::string::npos;
    });
  };
  EXPECT_TRUE(has_note(Diagnose(data), "sequence counter: no packet missing inside a segment"));
  const size_t at = data.thermal.size() / 2;
  const double t_gap = data.thermal[at + 37].t_s;
  data.thermal.erase(data.thermal.begin() + static_cast<std::ptrdiff_t>(at),
                     data.thermal.begin() + static_cast<std::ptrdiff_t>(at + 37));
  data.thermal_segment.erase(data.thermal_segment.begin() + static_cast<std::ptrdiff_t>(at),
                             data.thermal_segment.begin() + static_cast<std::ptrdiff_t>(at + 37));
  const UnitDiagnosis d = Diagnose(data);
  EXPECT_TRUE(has_note(
      d,
      fmt::format(
          "1 gap(s) inside segments, 37 packet(s) missing (the largest, 37, at t = {:.2f} s",
          t_gap)))
      << ::testing::PrintToString(d.notes);
}

// The per-row spread of a gyro's counts over the last soak (differences remove the slow drift).
double GyroRowSpreadCnt(const calib::ImuUnitData& data, int axis) {
  double sum2 = 0.0;
  const size_t n = 20000;
  for (size_t i = data.thermal.size() - n; i < data.thermal.size(); ++i) {
    const double d = static_cast<double>(data.thermal[i].raw.gyro_cnt[axis]) -
                     data.thermal[i - 1].raw.gyro_cnt[axis];
    sum2 += d * d;
  }
  return std::sqrt(sum2 / n / 2.0);
}

// A tone written onto one gyro's counts in every thermal, accelerometer and gyro row.
void AddGyroTone(calib::ImuUnitData* data, int axis, double amplitude_cnt, double f_hz, int phase) {
  auto add = [&](calib::ImuSample& s) {
    s.raw.gyro_cnt[axis] += static_cast<int32_t>(
        std::lround(amplitude_cnt * std::sin(2.0 * M_PI * f_hz * s.t_s + phase)));
  };
  for (calib::ImuSample& s : data->thermal) add(s);
  for (calib::ImuAcquisition& a : data->accel)
    for (calib::ImuSample& s : a.samples) add(s);
  for (calib::ImuAcquisition& a : data->gyro)
    for (calib::ImuSample& s : a.samples) add(s);
}

// Periodic interference (outside the library) at a fifth of the per-row noise: visible only in
// the rows' aggregated spectrum. On 10 units, each with a tone on one gyro at its own frequency,
// it is located within half a bin of its frequency and 15 % of its amplitude on at least 9, never
// on another channel, and never forced into a term.
TEST(ImuDiagnosis, LocatesPeriodicInterferenceBelowTheRowNoise) {
  Shape shape;
  shape.sensor_cal_c = {-20.0, 25.0, 70.0};  // the clean test's shape
  int located = 0;
  for (int unit = 0; unit < 10; ++unit) {
    calib::ImuUnitData data = Simulate(Nominal(610 + unit), 7010 + unit, shape);
    const int axis = unit % 3;
    const double f_hz = 1.5 + 4.3 * unit;  // 1.5 ... 40.2 Hz
    const double amplitude_cnt = 0.2 * GyroRowSpreadCnt(data, axis);
    AddGyroTone(&data, axis, amplitude_cnt, f_hz, unit);
    const DiagnosisData cells = BuildDiagnosisData(data, 9.80665);
    const UnitDiagnosis d = DiagnoseImu(cells);
    for (const Finding& f : d.findings) ADD_FAILURE() << f.words;
    const std::string channel = common::kImuChannelNames[6 + axis];
    for (const Unexplained& u : d.unexplained) EXPECT_EQ(u.channel, channel) << u.description;
    const std::vector<PeriodicLine> lines =
        FindPeriodicLines(cells.spectra, 6 + axis, 1e-3 / kImuChannels);
    const double bin_hz = cells.spectra.BinHz(1.0);
    for (const PeriodicLine& l : lines) {
      std::printf(
          "%s: injected %.0f counts at %.2f Hz; found %.0f counts at %.3f Hz (bin %.3f Hz) in %zu "
          "of %d segments\n",
          channel.c_str(),
          amplitude_cnt,
          f_hz,
          l.amplitude,
          l.frequency_hz,
          bin_hz,
          l.segments.size(),
          l.segments_with_windows);
    }
    if (d.unexplained.size() == 1 && lines.size() == 1 &&
        std::abs(lines[0].frequency_hz - f_hz) < bin_hz / 2 &&
        std::abs(lines[0].amplitude - amplitude_cnt) < 0.15 * amplitude_cnt) {
      ++located;
    }
  }
  EXPECT_GE(located, 9);
}

// Interference below the rows' windows' lowest searched bin (about 1.2 Hz at 512 rows of 10 ms):
// 0.3 ... 1.0 Hz at half the per-row noise, found by the slow windows at its frequency (within
// half a slow bin) and amplitude (15 %), on its channel only, on at least 7 of 8 units. Below
// about 0.5 Hz 1 s cells keep most of it (sin(pi f) / (pi f) = 0.86 at 0.3 Hz), so the held-out
// error on that channel stands above the noise as well, rightly; a term fitted to it is a false
// finding, allowed on at most 1 of the 8.
TEST(ImuDiagnosis, LocatesSlowPeriodicInterferenceBelowOneHertz) {
  Shape shape;
  shape.sensor_cal_c = {-20.0, 25.0, 70.0};
  int located = 0, with_findings = 0;
  for (int unit = 0; unit < 8; ++unit) {
    calib::ImuUnitData data = Simulate(Nominal(640 + unit), 7040 + unit, shape);
    const int axis = unit % 3;
    const double f_hz = 0.3 + 0.1 * unit;  // 0.3 ... 1.0 Hz
    const double amplitude_cnt = 0.5 * GyroRowSpreadCnt(data, axis);
    AddGyroTone(&data, axis, amplitude_cnt, f_hz, unit);
    const DiagnosisData cells = BuildDiagnosisData(data, 9.80665);
    const UnitDiagnosis d = DiagnoseImu(cells);
    for (const Finding& f : d.findings) std::printf("finding: %s\n", f.words.c_str());
    if (!d.findings.empty()) ++with_findings;
    const std::string channel = common::kImuChannelNames[6 + axis];
    const double half_bin_hz = cells.slow_spectra.BinHz(0.5);
    bool found = false;
    for (const Unexplained& u : d.unexplained) {
      std::printf("%s: injected %.0f counts at %.2f Hz; unexplained %s %s: %s\n",
                  channel.c_str(),
                  amplitude_cnt,
                  f_hz,
                  u.channel.c_str(),
                  u.where.c_str(),
                  u.description.c_str());
      EXPECT_EQ(u.channel, channel) << u.description;
      const size_t at = u.description.find("periodic ");
      if (u.channel != channel || at == std::string::npos) continue;
      const double found_hz = std::stod(u.description.substr(at + 9));
      const size_t amp = u.description.find("amplitude ");
      const double found_cnt =
          amp == std::string::npos ? 0.0 : std::stod(u.description.substr(amp + 10));
      if (std::abs(found_hz - f_hz) < half_bin_hz &&
          std::abs(found_cnt - amplitude_cnt) < 0.15 * amplitude_cnt)
        found = true;
    }
    if (found) ++located;
  }
  std::printf("slow tones: located on %d of 8 units, a finding on %d\n", located, with_findings);
  EXPECT_GE(located, 7);
  EXPECT_LE(with_findings, 1);
}

// On a real line packets arrive in bursts: their arrival times share values and jump. The row
// spectra take each row's time from the packet counter, so a tone is located as well from rows
// whose arrival times are quantised to 0.2 s (bursts of 20 packets) as from exact ones.
// Table rate ripple concealed below the row noise: a relative ripple of 4e-4 is 0.06 deg/s at
// 150 deg/s against about 0.3 deg/s of noise per row, and averages away in 1 s cells. With 30 s
// per rate it is found on the gyro along the table axis in each orientation, above its stated
// detection limit, sized within 3 standard errors on all but the binomial share (28 of 30), those
// errors bounded by the truth's scatter, with its held-out amplitude error below the line's; the
// same units without ripple give no ripple finding (at most 1 of 10). Other findings: the
// one-temperature shape's known false discoveries (g-sensitivity test), counted once per variant
// of a unit.
TEST(ImuDiagnosis, FindsTableRateRippleOnTheGyroAlongTheTableAxis) {
  Shape shape;
  shape.gyro_packets = 3000;
  constexpr double kRipple = 4e-4;
  int found = 0, within = 0, false_found = 0, others = 0;
  adahrs::testing::StandardErrorBound bound("table rate ripple");
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    for (const double k : {kRipple, 0.0}) {
      ImuScenario s(Nominal(700 + seed), 7700 + seed, 25.0);
      s.set_table_rate_ripple(k);
      s.ThermalProfile(31, shape.profile_c, shape.ramp_c_per_min, shape.soak_s);
      s.Soak(25.0, shape.settle_s);
      s.SensorCalibration(2, shape.accel_packets, shape.gyro_packets);
      const UnitDiagnosis d = Diagnose(s.data());
      for (const Finding& f : d.findings) {
        if (f.effect != "table_rate_ripple") {
          ++others;
          std::printf(
              "seed %d, k %g, not in the truth: %s\n", static_cast<int>(seed), k, f.words.c_str());
          continue;
        }
        if (k == 0.0) {
          ++false_found;
          std::printf("seed %d, clean: %s\n", static_cast<int>(seed), f.words.c_str());
          continue;
        }
        std::printf("seed %d: %s\n", static_cast<int>(seed), f.words.c_str());
        ++found;
        const double ratio_ppm = f.components[0].magnitude;
        within += std::abs(ratio_ppm - kRipple * 1e6) <= 3.0 * f.components[0].standard_error;
        bound.Add(ratio_ppm, f.components[0].standard_error, kRipple * 1e6);
        EXPECT_LT(f.held_out_rms_after, f.held_out_rms_before) << f.words;
      }
      if (k != 0.0) {
        const DetectionLimit* lim = Limit(d, "table_rate_ripple", "gz");
        ASSERT_NE(lim, nullptr);
        ASSERT_EQ(lim->limits.size(), 1u);
        EXPECT_LT(lim->limits[0].magnitude, kRipple * 1e6);
      }
    }
  }
  std::printf("table rate ripple: %d of 30 gyros found, %d within 3 SE; %d found without ripple\n",
              found,
              within,
              false_found);
  EXPECT_GE(found, 27);
  EXPECT_GE(within, adahrs::testing::RequiredWithinThreeSe(found));
  bound.Expect(27);
  EXPECT_LE(false_found, 1);
  EXPECT_LE(others, 4);
}

TEST(ImuDiagnosis, LocatesPeriodicInterferenceInRowsThatArriveInBursts) {
  Shape shape;
  int located = 0;
  for (int unit = 0; unit < 3; ++unit) {
    calib::ImuUnitData data = Simulate(Nominal(640 + unit), 7040 + unit, shape);
    const int axis = unit % 3;
    const double f_hz = 3.1 + 11.0 * unit;
    const double amplitude_cnt = 3000.0;
    auto add = [&](calib::ImuSample& s) {
      s.raw.gyro_cnt[axis] +=
          static_cast<int32_t>(std::lround(amplitude_cnt * std::sin(2.0 * M_PI * f_hz * s.t_s)));
      s.t_s = 0.2 * std::floor(s.t_s / 0.2);
    };
    for (calib::ImuSample& s : data.thermal) add(s);
    for (calib::ImuAcquisition& a : data.accel)
      for (calib::ImuSample& s : a.samples) add(s);
    for (calib::ImuAcquisition& a : data.gyro)
      for (calib::ImuSample& s : a.samples) add(s);
    const DiagnosisData cells = BuildDiagnosisData(data, 9.80665);
    const std::vector<PeriodicLine> lines =
        FindPeriodicLines(cells.spectra, 6 + axis, 1e-3 / kImuChannels);
    const double bin_hz = cells.spectra.BinHz(1.0);
    for (const PeriodicLine& l : lines) {
      std::printf(
          "bursts: injected %.0f counts at %.2f Hz; found %.0f counts at %.3f Hz (bin %.3f Hz), %d "
          "windows\n",
          amplitude_cnt,
          f_hz,
          l.amplitude,
          l.frequency_hz,
          bin_hz,
          cells.spectra.windows());
    }
    if (lines.size() == 1 && std::abs(lines[0].frequency_hz - f_hz) < bin_hz / 2 &&
        std::abs(lines[0].amplitude - amplitude_cnt) < 0.15 * amplitude_cnt) {
      ++located;
    }
  }
  EXPECT_EQ(located, 3);
}

// The three effects the pipeline's model does not calibrate, each alone in the truth on the clean
// test's shape: found on the channels whose stated detection limit the truth exceeds (at most
// 20 % missed), sized within 3 standard errors (plus a stated model allowance), nothing else.
struct EffectTally {
  explicit EffectTally(const std::string& what) : size(what) {}
  Tally size;
  int found = 0, missed = 0, detectable = 0, others = 0;
  void Print(const char* what) const {
    std::printf("%s: found on %d, %d of %d detectable missed, %d of %d within; %d others\n",
                what,
                found,
                missed,
                detectable,
                size.within,
                size.total,
                others);
  }
};

void Score(const UnitDiagnosis& d,
           const std::string& effect,
           int ch,
           double truth,
           double allowance,
           EffectTally* t) {
  const Finding* f = Find(d, effect, common::kImuChannelNames[ch]);
  bool can = false;
  for (const DetectionLimit& l : d.detection_limits) {
    if (l.channel == common::kImuChannelNames[ch] && l.effect.rfind(effect, 0) == 0 &&
        Detectable(&l, {truth}))
      can = true;
  }
  t->detectable += can;
  if (f == nullptr) {
    t->missed += can;
    return;
  }
  ++t->found;
  t->size.Check(f->components[0].magnitude, f->components[0].standard_error, truth, allowance);
}

void CountOthers(const UnitDiagnosis& d, const std::string& effect, EffectTally* t) {
  for (const Finding& f : d.findings) {
    if (f.effect == effect) continue;
    ++t->others;
    std::printf("  not in the truth: %s\n", f.words.c_str());
  }
}

void ExpectFoundAndSized(const EffectTally& t, int min_found, double documented_inflation = 1.0) {
  EXPECT_GE(t.found, min_found);
  EXPECT_LE(5 * t.missed, t.detectable);
  t.size.Expect(min_found, documented_inflation);
  EXPECT_LE(t.others, 1);
}

Shape CleanShape() {
  Shape shape;
  shape.sensor_cal_c = {-20.0, 25.0, 70.0};
  return shape;
}

// Accelerometer self-heating warm-up from the simulator: every die lags the air with tau 300 s,
// only the accelerometer chips heat themselves (3 degC), so each accelerometer's die starts
// 3 degC below its steady excess over its thermometer (a gyro die) and settles with tau 300 s.
TEST(ImuDiagnosis, FindsAccelerometerSelfHeatingWarmUp) {
  EffectTally t("accelerometer warm-up");
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    ImuUnitParams p = Nominal(920 + seed);
    for (auto& th : p.accel_thermal) th.effects = {true, true};
    for (auto& th : p.gyro_thermal) th.effects = {true, false};
    for (auto* a : {&p.accel_thermal, &p.gyro_thermal}) {
      for (auto& th : *a) th.tau_s = 300.0;
    }
    const UnitDiagnosis d = Diagnose(Simulate(p, 9200 + seed, CleanShape()));
    for (int ch = 0; ch < 6; ++ch) {
      const double truth = -p.accel_thermal[ch / 2].self_heating_c;
      Score(d, "self_heating_warm_up", ch, truth, 0.15 * std::abs(truth), &t);
    }
    CountOthers(d, "self_heating_warm_up", &t);
  }
  t.Print("accelerometer warm-up 3 degC");
  ExpectFoundAndSized(t, 24);
}

// Accelerometer nonlinearity from the simulator: D = D0 + S (a + k2 a^2) with the BFSL deviation
// of 1 % of 10 g (k2 = 1.5 mg/g^2, five times the datasheet's typical 0.2 %).
TEST(ImuDiagnosis, FindsAccelerometerNonlinearityBeyondTheCaptureQuantisation) {
  EffectTally t("accelerometer nonlinearity");
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    ImuUnitParams p = Nominal(940 + seed);
    for (auto& chip : p.accel_chips) {
      chip.effects.nonlinearity = true;
      chip.x.nonlinearity_pct_fs = 1.0;
      chip.y.nonlinearity_pct_fs = 1.0;
    }
    const UnitDiagnosis d = Diagnose(Simulate(p, 9400 + seed, CleanShape()));
    for (int ch = 0; ch < 6; ++ch) Score(d, "accel_nonlinearity", ch, 1.5, 0.0, &t);
    CountOthers(d, "accel_nonlinearity", &t);
  }
  t.Print("accelerometer nonlinearity 1.5 mg/g^2");
  // Its standard error carries the capture quantiser's worst-case bias per segment (an offset
  // uniform over one output step), which these units' ticks average well below: 3.2 times the
  // estimates' scatter about the truth (docs/diagnose.md), held there. Within 3 SE is therefore
  // a loose check of its size, and its detection limit is conservative by as much.
  ExpectFoundAndSized(t, 24, 3.2);
}

// Counts per deg/s of gyro g, measured on the recording's own 25 degC rate acquisitions about
// its axis (the line through the mean counts at each rate).
double GyroCountsPerDps(const calib::ImuUnitData& d, int g) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (const calib::ImuAcquisition& a : d.gyro) {
    if (calib::UpAxisOf(a.orientation)[g] == 0.0 ||
        std::abs(a.samples.front().chamber_c - 25.0) > 1.0)
      continue;
    double mean = 0.0;
    for (const calib::ImuSample& s : a.samples) mean += s.raw.gyro_cnt[g];
    mean /= static_cast<double>(a.samples.size());
    const double x = a.rate_dps * calib::UpAxisOf(a.orientation)[g];
    sx += x, sy += mean, sxx += x * x, sxy += x * mean, n += 1;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Gyro thermal hysteresis, which the simulator does not have, written onto the counts by the
// sense of the air's last change (tests/diagnosis/imu_diagnosis_scenario.h): a bias that differs
// after heating and after cooling at the same temperature, which a single-valued temperature
// polynomial splits between its branches.
TEST(ImuDiagnosis, FindsGyroThermalHysteresisBetweenHeatingAndCooling) {
  EffectTally t("gyro thermal hysteresis");
  double lo_dps = 1e9, hi_dps = 0.0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const double half_loop_dps = 0.1;
    const double h_cnt = half_loop_dps * kGyroDatasheetCountsPerDps;
    const calib::ImuUnitData data =
        Simulate(Nominal(960 + seed), 9600 + seed, CleanShape(), [&](ImuScenario& s) {
          s.set_gyro_thermal_hysteresis_cnt({h_cnt, -h_cnt, h_cnt});
        });
    const UnitDiagnosis d = Diagnose(data);
    for (int g = 0; g < 3; ++g) {
      const double truth_dps = (g == 1 ? -h_cnt : h_cnt) / GyroCountsPerDps(data, g);
      Score(d, "thermal_hysteresis", 6 + g, truth_dps, 0.0, &t);
      const DetectionLimit* l = Limit(d, "thermal_hysteresis", common::kImuChannelNames[6 + g]);
      if (l != nullptr && !l->limits.empty()) {
        lo_dps = std::min(lo_dps, l->limits[0].magnitude);
        hi_dps = std::max(hi_dps, l->limits[0].magnitude);
      }
    }
    CountOthers(d, "thermal_hysteresis", &t);
  }
  t.Print("gyro thermal hysteresis 0.1 deg/s");
  std::printf("gyro thermal hysteresis limits %.3g ... %.3g deg/s\n", lo_dps, hi_dps);
  ExpectFoundAndSized(t, 18);  // measured: 22 of 30, the others below the stated limit
}

// A cross-axis coupling that changes with temperature, which the simulator does not have, written
// onto the gyro counts: calibrated at one temperature it is a fixed misalignment, so it shows only
// in rate acquisitions about the other axes at -20 and 70 degC.
TEST(ImuDiagnosis, FindsResidualCrossAxisCouplingAwayFromTheCalibrationTemperature) {
  Tally tally("cross-axis tempco", 2);
  int detectable = 0, missed = 0, others = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const double k_ppm_per_c = 30.0;
    Eigen::Matrix3d k_ppm;
    k_ppm << 0, k_ppm_per_c, -k_ppm_per_c, -k_ppm_per_c, 0, k_ppm_per_c, k_ppm_per_c, -k_ppm_per_c,
        0;
    const calib::ImuUnitData data =
        Simulate(Nominal(980 + seed), 9800 + seed, CleanShape(), [&](ImuScenario& s) {
          s.set_gyro_cross_axis_tempco(k_ppm * 1e-6 * kGyroDatasheetCountsPerDps);
        });
    const UnitDiagnosis d = Diagnose(data);
    for (int g = 0; g < 3; ++g) {
      const double sens = GyroCountsPerDps(data, g) / kGyroDatasheetCountsPerDps;
      std::vector<double> truth;
      for (int j = 0; j < 3; ++j) {
        if (j != g) truth.push_back(k_ppm(g, j) / sens);
      }
      const std::string ch = common::kImuChannelNames[6 + g];
      const bool can = Detectable(Limit(d, "residual_cross_axis_coupling", ch), truth);
      detectable += can;
      const Finding* f = Find(d, "residual_cross_axis_coupling", ch);
      if (f == nullptr) {
        missed += can;
        continue;
      }
      for (size_t k = 0; k < 2; ++k)
        tally.Check(f->components[k].magnitude, f->components[k].standard_error, truth[k]);
    }
    for (const Finding& f : d.findings) {
      if (f.effect == "residual_cross_axis_coupling" && f.channel[0] == 'g') continue;
      ++others;
      std::printf("seed %d, not in the truth: %s\n", static_cast<int>(seed), f.words.c_str());
    }
  }
  std::printf("cross-axis tempco: %d of %d components within 3 SE; %d of %d detectable missed\n",
              tally.within,
              tally.total,
              missed,
              detectable);
  EXPECT_GE(detectable, 24);
  EXPECT_LE(5 * missed, detectable);
  tally.Expect(24);
  EXPECT_LE(others, 2);
}

// Truth-profile units (every modelled effect on at once) through the demo's calibration shape:
// the full thermal profile (25 -> -40 -> 25 -> 85 -> 25 degC at 1 degC/min, 1 h soaks) in
// orientation 31, then the sensor calibration at 25 degC. Die lag is found on every accelerometer
// channel and g-sensitivity on most gyros, sized within 3 SE + 15 % (lag) or 3 SE; scale factor
// vs temperature stays undetectable from one calibration temperature.
TEST(ImuDiagnosis, TruthProfileUnitsOnTheDemosShape) {
  Tally lag("truth profile, die lag"), gsens("truth profile, g-sensitivity", 3);
  int gyros_found = 0;
  for (uint64_t seed : {1, 2}) {
    const ImuUnitParams p = ImuUnitParams::Draw("IMU-0001", seed, ModelProfile::kTruth);
    ImuScenario s(p, 77 + seed, 25.0);
    s.Soak(25.0, 1800.0);
    s.ThermalProfile(31, {-40.0, 25.0, 85.0, 25.0}, 1.0, 3600.0);
    s.Soak(25.0, 1800.0);
    s.SensorCalibration(4, 1000, 1000);
    const UnitDiagnosis d = Diagnose(s.data());
    for (int ch = 0; ch < 6; ++ch) {
      const double truth = p.accel_thermal[ch / 2].tau_s -
                           p.gyro_thermal[common::kImuChannels[ch].thermometer].tau_s;
      const Finding* f = Find(d, "die_thermal_lag", common::kImuChannelNames[ch]);
      ASSERT_NE(f, nullptr) << "seed " << seed << " " << common::kImuChannelNames[ch];
      lag.Check(f->components[0].magnitude,
                f->components[0].standard_error,
                truth,
                0.15 * std::abs(truth));
    }
    for (int g = 0; g < 3; ++g) {
      const Eigen::Vector3d truth_B = p.geometry.R_GB(g).transpose() *
                                      Eigen::Vector3d(p.gyros[g].g_sensitivity_dps_per_g.data());
      const Finding* f = Find(d, "gyro_g_sensitivity", common::kImuChannelNames[6 + g]);
      if (f == nullptr) continue;
      ++gyros_found;
      for (int k = 0; k < 3; ++k)
        gsens.Check(f->components[k].magnitude, f->components[k].standard_error, truth_B[k]);
    }
    for (const Finding& f : d.findings) {
      EXPECT_NE(f.effect, "scale_factor_tempco") << f.words;
      EXPECT_NE(f.effect, "thermal_hysteresis") << f.words;  // the simulator's IMU has none
    }
  }
  std::printf(
      "truth profile, demo shape: lag %d of %d within 3 SE + 15 %%; g-sensitivity on %d of 6 "
      "gyros, "
      "%d of %d components within 3 SE\n",
      lag.within,
      lag.total,
      gyros_found,
      gsens.within,
      gsens.total);
  lag.Expect(12);
  EXPECT_GE(gyros_found, 4);
  gsens.Expect(4);
}

// The campaign sets each finding beside the rig's truth file, and lists what the truth has that
// the diagnosis did not report, with the diagnosis's reason (here: not testable).
TEST(ImuDiagnosis, CampaignComparesFindingsWithTheTruthFile) {
  ImuUnitParams p = Nominal(801);
  for (auto& g : p.gyros) g.effects.g_sensitivity = true;
  p.gyros[0].effects.sensitivity_tempco = true;  // not excited by one calibration temperature
  const UnitDiagnosis d = Diagnose(Simulate(p, 9001, Shape{}));
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "diagnosis_truth";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / (p.serial + ".json"))
      << nlohmann::json{{"serial", p.serial}, {"kind", "imu"}, {"params", p.ToJson()}}.dump();
  const std::vector<proving::DiagnosisTruthLine> lines =
      proving::CompareDiagnosisWithTruth({d}, dir);
  int found_gsens = 0, scale_not_found = 0;
  for (const proving::DiagnosisTruthLine& l : lines) {
    std::printf(
        "%s %s %s: %s\n", l.serial.c_str(), l.channel.c_str(), l.effect.c_str(), l.text.c_str());
    if (l.effect == "gyro_g_sensitivity" && l.found) ++found_gsens;
    if (l.effect == "scale_factor_tempco" && l.channel == "gx" && !l.found) {
      ++scale_not_found;
      // One calibration temperature gives the tempco no leverage: said so, not a limit of 10^5.
      EXPECT_NE(l.text.find("not testable here"), std::string::npos) << l.text;
    }
  }
  EXPECT_EQ(found_gsens, 3);
  EXPECT_EQ(scale_not_found, 1);
  EXPECT_THROW(proving::CompareDiagnosisWithTruth({d}, dir / "missing"), std::exception);
}

// The output contract: format, version, one finding's fields, every candidate's limit.
TEST(ImuDiagnosis, WritesTheDocumentedJsonContract) {
  ImuUnitParams p = Nominal(701);
  for (auto& g : p.gyros) g.effects.g_sensitivity = true;
  const UnitDiagnosis d = Diagnose(Simulate(p, 8001, Shape{}));
  const nlohmann::json j = d.ToJson();
  ASSERT_FALSE(j["findings"].empty());
  const nlohmann::json& f = j["findings"][0];
  for (const char* key : {"effect",
                          "channels",
                          "magnitude",
                          "standard_error",
                          "unit",
                          "held_out_rms_before",
                          "held_out_rms_after",
                          "evidence",
                          "words",
                          "components"}) {
    EXPECT_TRUE(f.contains(key)) << key;
  }
  // Accelerometers: lag, scale tempco, warm-up at 4 time constants, nonlinearity; gyros: scale
  // tempco, residual cross-axis coupling, g-sensitivity, thermal hysteresis, table rate ripple.
  EXPECT_EQ(j["detection_limits"].size(), 6u * 7u + 3u * 5u);
  // This shape's 3 s rate acquisitions hold less than 3 turns: the ripple is untestable, and says
  // why.
  for (const nlohmann::json& l : j["detection_limits"]) {
    if (l["effect"] != "table_rate_ripple") continue;
    EXPECT_TRUE(l["limits"].is_null());
    EXPECT_NE(l["note"].get<std::string>().find("3 turns"), std::string::npos);
  }
}
}  // namespace
}  // namespace adahrs::diagnosis
