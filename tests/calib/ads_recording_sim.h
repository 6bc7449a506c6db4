// Test helper: an ADS calibration or acceptance recording written in-process as the executor
// would (contract C2): the shipped sequence is expanded (calib/sequence/execution_plan.h) and run
// against one simulated ADS unit (sensor_sim::AdsUnit) with an ideal chamber and air data test
// set; every acquired packet is a row carrying the action's TAG, the reference columns are the
// applied pressures (an exact test set), the chamber column the commanded air temperature.
// Simplifications, each harmless to what the tests check: the test set moves the pressures as
// monotone jumps (the bridges' hysteresis is rate independent, so the branches are the same;
// slew time would only let the die settle further), the chamber air reaches its set point at once
// and the soak runs at frame rate (so the die's thermal lag is simulated), WaitAdtsStable logs
// 1 s of untagged packets (tag 0: not calibration data), packets are never lost.
#pragma once

#include <filesystem>
#include <string>
#include <variant>
#include "adahrs_build_paths.h"

#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_json.h"
#include "calib/sequence/sequence_limits.h"
#include "hil/recording/recording_writer.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/air_data.h"
#include "sensor_sim/atmosphere.h"

namespace adahrs::calib::testing {

inline std::string ShippedSequencePath(const std::string& name) {
  return std::string(ADAHRS_SOURCE_DIR) + "/calib/sequences/" + name + ".json";
}

/// Runs sequence file `sequence_path` on a unit with `params` and writes the run to `run_dir`.
inline void WriteAdsRecording(const std::filesystem::path& run_dir,
                              const std::string& sequence_path,
                              const sensor_sim::AdsUnitParams& params,
                              uint64_t noise_seed) {
  const ParsedSequence parsed = ParseSequenceFile(sequence_path);
  const ExecutionPlan plan = ExpandSequence(parsed.sequence, SequenceLimits{});
  hil::RecordingWriter writer(run_dir);
  writer.WriteMeta({{"run_id", "ads-test"},
                    {"status", "complete"},
                    {"sample_rate_hz", 100},
                    {"units", {{{"kind", "ads"}, {"serial", params.serial}}}},
                    {"rejected_intervals", nlohmann::json::array()}});
  double air_c = 25.0;
  sensor_sim::AdsStimulus stimulus;
  stimulus.air_temp_c = air_c;
  stimulus.oat_c = air_c;
  sensor_sim::AdsUnit unit(params, noise_seed, air_c);
  double t_s = 0.0;
  uint32_t seq = 0;
  auto frame = [&](int step, uint8_t tag, bool write) {
    const sensor_sim::AdsRawFrame f = unit.Step(stimulus);
    t_s += params.frame_period_s;
    seq = (seq + 1) & 0xFF;
    if (!write) return;
    hil::AdsRecordRow row;
    row.t_s = t_s;
    row.unit = params.serial;
    row.seq = seq;
    row.step = step;
    row.tag = tag;
    row.chamber_c = air_c;
    row.ps_ref_pa = stimulus.ps_pa;
    row.qc_ref_pa = stimulus.qc_pa;
    row.ps_counts = f.ps_cnt;
    row.pt_counts = f.pt_cnt;
    row.ps_temp_counts = f.ps_temp_cnt;
    row.pt_temp_counts = f.pt_temp_cnt;
    row.oat_counts = f.oat_cnt;
    writer.Append(row);
  };
  const int frames_per_s = static_cast<int>(1.0 / params.frame_period_s + 0.5);
  for (const PlannedAction& a : plan.actions) {
    const int step = static_cast<int>(a.step);
    if (const auto* set = std::get_if<SetChamberSetPoint>(&a.action)) {
      air_c = set->temp_c;
      stimulus.air_temp_c = air_c;
      stimulus.oat_c = air_c;
    } else if (const auto* soak = std::get_if<WaitChamberSoak>(&a.action)) {
      for (int i = 0; i < static_cast<int>(soak->soak_s) * frames_per_s; ++i) frame(step, 0, false);
    } else if (const auto* alt = std::get_if<SetAltitude>(&a.action)) {
      stimulus.ps_pa = sensor_sim::IsaStaticPressurePaFromFt(alt->alt_ft);
    } else if (const auto* cas = std::get_if<SetAirspeed>(&a.action)) {
      stimulus.qc_pa = sensor_sim::ImpactPressurePaFromKt(cas->cas_kt);
    } else if (std::holds_alternative<WaitAdtsStable>(a.action)) {
      for (int i = 0; i < frames_per_s; ++i) frame(step, 0, true);
    } else if (const auto* acquire = std::get_if<AcquirePackets>(&a.action)) {
      for (int64_t i = 0; i < acquire->packets; ++i) frame(step, a.tag, true);
    }
  }
  writer.Flush(true);
}

}  // namespace adahrs::calib::testing
