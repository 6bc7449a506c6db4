// Test helper: writes small acceptance recordings in recording format 2 (docs/recording-format.md)
// whose compensated columns carry KNOWN errors against the instruments' reported reference, so
// the acceptance verdicts have a truth to be checked against:
//   IMU (mode 3 or 2): measured = reference + error + N(0, noise), where the reference is the
//     orientation's up axis times local gravity and the table's REPORTED rate about it
//     (command + table_rate_error_dps, as a real table reports within 0.01 deg/s); thermal profile
//     ramps move the chamber by thermal_step_c per packet with the unit in thermal_orientation;
//   ADS (mode 1): the test set reports ps/qc of aim + reference_offset, the unit reads the
//     reported reference + error + N(0, noise).
// Errors are given per unit (and per quantity); noise has a fixed seed.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/sequence/sequence.h"
#include "calib/sequence/sequence_json.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "common/units.h"
#include "hil/recording/recording_writer.h"

namespace adahrs::calib::testing {

inline constexpr double kTestGLocal_mps2 = 9.7965;

struct ImuErrors {
  std::array<double, 3> accel_mg{};  ///< added to f_B, per axis
  std::array<double, 3> rate_dps{};  ///< added to w_B, per axis
  double accel_mg_per_c = 0.0;       ///< added to f_B on every axis per degC away from 25 degC
  double noise_mg = 0.3;
  double noise_dps = 0.003;
  int mode = 3;
};

struct AdsErrors {
  double alt_ft = 0.0;
  double cas_kt = 0.0;
  double noise_ft = 2.0;
  double noise_kt = 0.05;
};

/// Rows of one (unit, step) may be rewritten before they are written (malformed-input tests).
using ImuRowEdit = std::function<bool(hil::ImuRecordRow&)>;  ///< false drops the row
using AdsRowEdit = std::function<bool(hil::AdsRecordRow&)>;

class AcceptanceRecordingMaker {
 public:
  int packets = 100;
  double chamber_c = 25.0;
  double table_rate_error_dps = 0.004;
  double reference_offset_ft = 3.0;  ///< the test set's altitude differs from the aim
  double reference_offset_kt = 0.3;
  double thermal_step_c = 0.05;  ///< chamber change per packet on a thermal profile ramp
  int thermal_orientation = 31;
  /// IMU: packets logged at rest (tag 0, thermal_orientation) at each target temperature step,
  /// as a soak logs them: the rest record the judge reads the units' noise from.
  int rest_packets = 0;
  ImuRowEdit imu_edit;
  AdsRowEdit ads_edit;

  void RunImu(const Sequence& sequence,
              const std::map<std::string, ImuErrors>& units,
              const std::filesystem::path& run_dir) {
    Begin(run_dir);
    const std::vector<uint8_t> tags = EffectiveTags(sequence);
    for (size_t s = 0; s < sequence.steps.size(); ++s) {
      const StepBody& body = sequence.steps[s].body;
      if (const auto* t = std::get_if<TargetTemperatureStep>(&body)) {
        chamber_c = t->target_c;
        const int saved = packets;
        packets = rest_packets;
        ImuFrames(units, static_cast<int>(s), 0, thermal_orientation, 0.0);
        packets = saved;
      }
      if (const auto* a = std::get_if<AccelStep>(&body)) {
        ImuFrames(units, static_cast<int>(s), tags[s], a->orientation, 0.0);
      }
      if (const auto* g = std::get_if<GyroStep>(&body)) {
        for (double r : GyroRates_dps(*g))
          ImuFrames(units, static_cast<int>(s), tags[s], g->orientation, r);
      }
      if (const auto* c = std::get_if<CrossAxisStep>(&body)) {
        for (int o : kCrossAxisOrientations) {
          for (double r : {0.0, c->rate_dps}) ImuFrames(units, static_cast<int>(s), tags[s], o, r);
        }
      }
      if (const auto* p = std::get_if<ThermalProfileStep>(&body)) {
        // Ramps move the chamber by thermal_step_c per packet; soaks last `packets` packets.
        const int saved = packets;
        packets = 1;
        for (const F4ProfileStep& ps : p->steps) {
          if (const auto* r = std::get_if<F4RampRate>(&ps)) {
            while (std::abs(r->target_c - chamber_c) > 1e-9) {
              const double step_c = std::min(thermal_step_c, std::abs(r->target_c - chamber_c));
              chamber_c += r->target_c > chamber_c ? step_c : -step_c;
              ImuFrames(units, static_cast<int>(s), tags[s], thermal_orientation, 0.0);
            }
          }
          if (std::holds_alternative<F4Soak>(ps)) {
            for (int i = 0; i < saved; ++i)
              ImuFrames(units, static_cast<int>(s), tags[s], thermal_orientation, 0.0);
          }
        }
        packets = saved;
      }
    }
    End(sequence, run_dir, units, "imu");
  }

  void RunAds(const Sequence& sequence,
              const std::map<std::string, AdsErrors>& units,
              const std::filesystem::path& run_dir) {
    Begin(run_dir);
    const std::vector<uint8_t> tags = EffectiveTags(sequence);
    double alt_ft = 0.0, cas_kt = 0.0;
    for (size_t s = 0; s < sequence.steps.size(); ++s) {
      const StepBody& body = sequence.steps[s].body;
      if (const auto* t = std::get_if<TargetTemperatureStep>(&body)) chamber_c = t->target_c;
      if (const auto* a = std::get_if<AltitudeStep>(&body)) alt_ft = a->alt_ft;
      if (const auto* a = std::get_if<AirspeedStep>(&body)) cas_kt = a->cas_kt;
      if (std::holds_alternative<LogStep>(body)) {
        const double ref_alt_ft = alt_ft + reference_offset_ft;
        const double ref_cas_kt = cas_kt > 0.0 ? cas_kt + reference_offset_kt : 0.0;
        for (int i = 0; i < packets; ++i) {
          for (const auto& [serial, e] : units) {
            hil::AdsRecordRow row;
            row.t_s = t_s_;
            row.unit = serial;
            row.seq = seq_ & 0xFF;
            row.step = static_cast<int>(s);
            row.tag = tags[s];
            row.chamber_c = chamber_c;
            row.ps_ref_pa = common::IsaStaticPressurePaFromFt(ref_alt_ft);
            row.qc_ref_pa = common::ImpactPressurePaFromKt(ref_cas_kt);
            row.ps_cnt = 1000;
            row.pt_cnt = 1000;
            row.mode = 1;
            row.alt_ft = ref_alt_ft + e.alt_ft + e.noise_ft * normal_(rng_);
            row.cas_kt = ref_cas_kt + e.cas_kt + e.noise_kt * normal_(rng_);
            if (!ads_edit || ads_edit(row)) writer_->Append(row);
          }
          Tick();
        }
      }
    }
    End(sequence, run_dir, units, "ads");
  }

 private:
  void Begin(const std::filesystem::path& run_dir) {
    std::filesystem::remove_all(run_dir);
    writer_ = std::make_unique<hil::RecordingWriter>(run_dir);
  }

  template <typename Errors>
  void End(const Sequence& sequence,
           const std::filesystem::path& run_dir,
           const std::map<std::string, Errors>& units,
           const std::string& kind) {
    nlohmann::json unit_list = nlohmann::json::array();
    int slot = 1;
    for (const auto& [serial, e] : units) {
      unit_list.push_back({{"role", kind + std::to_string(slot)},
                           {"kind", kind},
                           {"serial", serial},
                           {"serial_number", slot},
                           {"firmware", "1.0.0"},
                           {"slot", slot},
                           {"constants_version", 1},
                           {"mode", kind == "imu" ? 3 : 1}});
      ++slot;
    }
    writer_->WriteMetaJson({{"run_id", "acceptance-test"},
                            {"started_utc", "2026-11-22T12:00:00Z"},
                            {"status", "complete"},
                            {"sequence", nlohmann::json::parse(SequenceToJson(sequence).dump())},
                            {"sequence_file", sequence.name + ".json"},
                            {"time_base", "pipeline clock seconds since the run started"},
                            {"sample_rate_hz", 100},
                            {"local_gravity_mps2", kTestGLocal_mps2},
                            {"units", unit_list},
                            {"instruments", nlohmann::json::array()},
                            {"rejected_intervals", nlohmann::json::array()}});
    writer_->Flush(true);
    writer_.reset();
    (void)run_dir;
  }

  void ImuFrames(const std::map<std::string, ImuErrors>& units,
                 int step,
                 uint8_t tag,
                 int orientation,
                 double rate_dps) {
    std::array<double, 3> up{};
    up[static_cast<size_t>(orientation / 10 - 1)] = orientation % 10 == 1 ? 1.0 : -1.0;
    const double reported_dps = rate_dps == 0.0 ? 0.0 : rate_dps + table_rate_error_dps;
    for (int i = 0; i < packets; ++i) {
      for (const auto& [serial, e] : units) {
        hil::ImuRecordRow row;
        row.t_s = t_s_;
        row.unit = serial;
        row.seq = seq_ & 0xFF;
        row.step = step;
        row.tag = tag;
        row.orientation = orientation;
        row.chamber_c = chamber_c;
        row.table_rate_dps = reported_dps;
        for (int ch = 0; ch < 6; ++ch) {
          row.accel_ticks[2 * ch] = 500;
          row.accel_ticks[2 * ch + 1] = 1000;
        }
        row.gyro_cnt = {4200000, 4200000, 4200000};
        row.temp_cnt = {30000, 30000, 30000};
        row.mode = static_cast<uint8_t>(e.mode);
        std::array<double, 3> f_g{}, w_dps{};
        for (size_t k = 0; k < 3; ++k) {
          f_g[k] =
              up[k] * common::Mps2ToG(kTestGLocal_mps2) +
              (e.accel_mg[k] + e.accel_mg_per_c * (chamber_c - 25.0) + e.noise_mg * normal_(rng_)) /
                  1000.0;
          w_dps[k] = up[k] * reported_dps + e.rate_dps[k] + e.noise_dps * normal_(rng_);
        }
        std::array<double, 9> comp{};
        if (e.mode == 3) {
          for (size_t k = 0; k < 3; ++k) {
            comp[k] = common::GToMps2(f_g[k]);
            comp[3 + k] = w_dps[k];
          }
        } else {
          // Mode 2: az1 ax1 ay1 az2 ax2 ay2, each g along its body axis; the pair disagrees by
          // +-0.7 mg, which the axis mean cancels.
          const double d = 0.7e-3;
          comp = {f_g[2] + d,
                  f_g[0] + d,
                  f_g[1] + d,
                  f_g[2] - d,
                  f_g[0] - d,
                  f_g[1] - d,
                  w_dps[0],
                  w_dps[1],
                  w_dps[2]};
        }
        if (e.mode != 0) row.comp = comp;
        if (!imu_edit || imu_edit(row)) writer_->Append(row);
      }
      Tick();
    }
  }

  void Tick() {
    ++seq_;
    t_s_ += 0.01;
  }

  std::unique_ptr<hil::RecordingWriter> writer_;
  std::mt19937_64 rng_{20261122};
  std::normal_distribution<double> normal_{0.0, 1.0};
  uint32_t seq_ = 0;
  double t_s_ = 0.0;
};

inline Sequence ImuAcceptanceSequence() {
  Sequence s;
  s.name = "imu_acceptance_test";
  s.unit_kind = UnitKind::kImu;
  s.steps.push_back({std::nullopt, TargetTemperatureStep{25.0, 0.5, 0.0}});
  for (int o : {11, 21, 31}) s.steps.push_back({std::nullopt, AccelStep{o, 100}});
  for (int o : {11, 21, 31}) {
    s.steps.push_back({std::nullopt, GyroStep{o, 100, -125.0, 125.0, 125.0, 100.0}});
  }
  return s;
}

inline Sequence AdsAcceptanceSequence() {
  Sequence s;
  s.name = "ads_acceptance_test";
  s.unit_kind = UnitKind::kAds;
  s.steps.push_back({std::nullopt, TargetTemperatureStep{25.0, 1.0, 0.0}});
  for (double alt : {5000.0, 20000.0}) {
    s.steps.push_back({std::nullopt, AltitudeStep{alt, 3000.0}});
    s.steps.push_back({std::nullopt, LogStep{100, std::nullopt}});
  }
  s.steps.push_back({std::nullopt, AltitudeStep{0.0, 3000.0}});
  s.steps.push_back({std::nullopt, AirspeedStep{100.0, 100.0}});
  s.steps.push_back({std::nullopt, LogStep{100, std::nullopt}});
  return s;
}

}  // namespace adahrs::calib::testing

namespace adahrs::calib::testing {

/// Cross-axis acceptance: 1 g and 150 deg/s along x, y, z (orientations 11, 21, 31).
inline Sequence CrossAxisAcceptanceSequence() {
  Sequence s;
  s.name = "imu_cross_axis_acceptance_test";
  s.unit_kind = UnitKind::kImu;
  s.steps.push_back({std::nullopt, CrossAxisStep{100, 150.0, 100.0}});
  return s;
}

/// Thermal acceptance: the unit at rest in orientation 31 while the chamber goes 25 -> -20 -> 25
/// degC.
inline Sequence ThermalAcceptanceSequence() {
  Sequence s;
  s.name = "imu_thermal_acceptance_test";
  s.unit_kind = UnitKind::kImu;
  s.steps.push_back({std::nullopt, TargetTemperatureStep{25.0, 0.5, 0.0}});
  s.steps.push_back(
      {std::nullopt,
       ThermalProfileStep{
           "ACCEPT", {F4RampRate{-20.0, 1.0}, F4Soak{600.0}, F4RampRate{25.0, 1.0}, F4End{}}}});
  return s;
}

}  // namespace adahrs::calib::testing
