#include "proving/studies/ads_run_simulator.h"

#include <cmath>
#include <variant>

#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_limits.h"
#include "common/air_data.h"
#include "common/atmosphere.h"

namespace adahrs::proving {
namespace {

// The columns at the resolution ads.csv writes them (hil/recording/recording_writer.cc: t_s to
// 0.1 ms, chamber_c to 0.001 degC, the reference pressures to 0.01 Pa).
double Rounded(double value, double per_unit) { return std::round(value * per_unit) / per_unit; }

}  // namespace

AdsRunSimulator::AdsRunSimulator(const sensor_sim::AdsUnitParams& params,
                                 uint64_t noise_seed,
                                 AdsRunSimulatorOptions options)
    : params_(params), unit_(params, noise_seed, options.initial_air_temp_c), options_(options) {
  stimulus_.air_temp_c = options.initial_air_temp_c;
  stimulus_.oat_c = options.initial_air_temp_c;
}

void AdsRunSimulator::Frames(int64_t n, int step, uint8_t tag, const AdsRowSink* sink) {
  hil::AdsRecordRow row;
  row.unit = params_.serial;
  row.step = step;
  row.tag = tag;
  row.chamber_c = Rounded(stimulus_.air_temp_c, 1e3);
  row.ps_ref_pa = Rounded(stimulus_.ps_pa, 1e2);
  row.qc_ref_pa = Rounded(stimulus_.qc_pa, 1e2);
  for (int64_t i = 0; i < n; ++i) {
    const sensor_sim::AdsRawFrame f = unit_.Step(stimulus_);
    t_s_ += params_.frame_period_s;
    seq_ = (seq_ + 1) & 0xFF;
    if (!sink) continue;
    row.t_s = Rounded(t_s_, 1e4);
    row.seq = seq_;
    row.ps_cnt = f.ps_cnt;
    row.pt_cnt = f.pt_cnt;
    row.ps_temp_cnt = f.ps_temp_cnt;
    row.pt_temp_cnt = f.pt_temp_cnt;
    row.oat_cnt = f.oat_cnt;
    (*sink)(row);
  }
}

void AdsRunSimulator::Run(const calib::Sequence& sequence, const AdsRowSink& sink) {
  const calib::ExecutionPlan plan = calib::ExpandSequence(sequence, calib::SequenceLimits{});
  const int frames_per_s = static_cast<int>(1.0 / params_.frame_period_s + 0.5);
  for (const calib::PlannedAction& a : plan.actions) {
    const int step = static_cast<int>(a.step);
    if (const auto* set = std::get_if<calib::SetChamberSetPoint>(&a.action)) {
      stimulus_.air_temp_c = set->temp_c;
      stimulus_.oat_c = set->temp_c;
    } else if (const auto* soak = std::get_if<calib::WaitChamberSoak>(&a.action)) {
      Frames(static_cast<int64_t>(soak->soak_s) * frames_per_s, step, 0, nullptr);
    } else if (const auto* alt = std::get_if<calib::SetAltitude>(&a.action)) {
      stimulus_.ps_pa = common::IsaStaticPressurePaFromFt(alt->alt_ft);
    } else if (const auto* cas = std::get_if<calib::SetAirspeed>(&a.action)) {
      stimulus_.qc_pa = common::ImpactPressurePaFromKt(cas->cas_kt);
    } else if (std::holds_alternative<calib::WaitAdtsStable>(a.action)) {
      Frames(std::llround(options_.settle_s * frames_per_s), step, 0, &sink);
    } else if (const auto* acquire = std::get_if<calib::AcquirePackets>(&a.action)) {
      Frames(acquire->packets, step, a.tag, &sink);
    }
  }
}

hil::Recording AdsRunRecording(const calib::Sequence& sequence,
                               const sensor_sim::AdsUnitParams& params,
                               uint64_t noise_seed,
                               AdsRunSimulatorOptions options) {
  hil::Recording recording;
  recording.meta.format_version = 1;
  recording.meta.run_id = "simulated " + sequence.name;
  recording.meta.status = "complete";
  recording.meta.sample_rate_hz = 100.0;
  recording.meta.sequence = nlohmann::json{{"name", sequence.name}};
  hil::RecordingUnit unit;
  unit.kind = common::UnitKind::kAds;
  unit.serial = params.serial;
  recording.meta.units = {unit};
  recording.meta.has_units = true;
  recording.meta.has_rejected_intervals = true;
  AdsRunSimulator simulator(params, noise_seed, options);
  simulator.Run(sequence, [&](const hil::AdsRecordRow& row) { recording.ads.push_back(row); });
  return recording;
}

}  // namespace adahrs::proving
