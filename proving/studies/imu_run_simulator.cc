#include "proving/studies/imu_run_simulator.h"

#include <cmath>
#include <variant>

#include "calib/sequence/execution_plan.h"
#include "common/units.h"

namespace adahrs::proving {
namespace {
constexpr double kFramePeriod_s = 0.01;

// The instrument columns at the resolution imu.csv writes them (hil/recording/recording_writer.cc:
// t_s to 0.1 ms, chamber_c to 0.001 degC, table_rate_dps to 0.0001 deg/s), so that the rows
// handed over in memory equal those a reader gets back from the recording.
hil::ImuRecordRow AtRecordedResolution(hil::ImuRecordRow row) {
  row.t_s = std::round(row.t_s * 1e4) / 1e4;
  row.chamber_c = std::round(row.chamber_c * 1e3) / 1e3;
  row.table_rate_dps = std::round(row.table_rate_dps * 1e4) / 1e4;
  return row;
}

}  // namespace

ImuRunSimulator::ImuRunSimulator(std::vector<sensor_sim::ImuUnitParams> units,
                                 double g_local_mps2,
                                 uint64_t noise_seed,
                                 ImuRunSimulatorOptions options)
    : params_(std::move(units)), g_local_mps2_(g_local_mps2), options_(options) {
  air_c_ = options_.initial_air_temp_c;
  for (size_t i = 0; i < params_.size(); ++i) {
    units_.push_back(
        std::make_unique<sensor_sim::ImuUnit>(params_[i], noise_seed + 101 * i, air_c_));
  }
}

void ImuRunSimulator::Frames(int64_t n, uint8_t tag) {
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  if (orientation_ != 0) up[orientation_ / 10 - 1] = orientation_ % 10 == 1 ? 1.0 : -1.0;
  sensor_sim::ImuStimulus stimulus;
  stimulus.f_B_g = up * common::Mps2ToG(g_local_mps2_);
  stimulus.w_B_dps = up * rate_dps_;
  hil::ImuRecordRow row;
  row.step = step_;
  row.tag = tag;
  row.orientation = orientation_;
  row.table_rate_dps = rate_dps_ == 0.0 ? 0.0 : rate_dps_ + options_.table_rate_error_dps;
  for (int64_t i = 0; i < n; ++i) {
    stimulus.air_temp_c = air_c_;
    row.t_s = t_s_;
    row.seq = seq_ & 0xFF;
    row.chamber_c = std::round(air_c_ * 10.0) / 10.0;
    for (size_t u = 0; u < units_.size(); ++u) {
      const sensor_sim::ImuRawFrame f = units_[u]->Step(stimulus);
      row.unit = params_[u].serial;
      for (int ch = 0; ch < 6; ++ch) {
        row.accel_ticks[2 * ch] = f.accel[ch].t1_cnt;
        row.accel_ticks[2 * ch + 1] = f.accel[ch].t2_cnt;
      }
      for (int g = 0; g < 3; ++g) {
        row.gyro_cnt[g] = f.gyro_cnt[g];
        row.temp_cnt[g] = f.temp_cnt[g];
      }
      (*sink_)(AtRecordedResolution(row));
    }
    ++seq_;
    t_s_ += kFramePeriod_s;
  }
}

void ImuRunSimulator::Ramp(double target_c, double rate_c_per_min, uint8_t tag) {
  const double step_c = rate_c_per_min / 60.0 * kFramePeriod_s * options_.thermal_speedup;
  while (std::abs(target_c - air_c_) > step_c) {
    air_c_ += target_c > air_c_ ? step_c : -step_c;
    Frames(1, tag);
  }
  air_c_ = target_c;
}

// The F4 engine's order: a jump goes back `count` times, then the profile goes on.
void ImuRunSimulator::RunProfile(const calib::ThermalProfileStep& profile, uint8_t tag) {
  std::vector<int> jumps_left(profile.steps.size(), -1);
  for (size_t i = 0; i < profile.steps.size();) {
    const hil::F4ProfileStep& s = profile.steps[i];
    if (const auto* r = std::get_if<hil::F4RampRate>(&s)) Ramp(r->target_c, r->rate_c_per_min, tag);
    if (const auto* r = std::get_if<hil::F4RampTime>(&s)) {
      Ramp(r->target_c, std::abs(r->target_c - air_c_) / (r->duration_s / 60.0), tag);
    }
    if (const auto* k = std::get_if<hil::F4Soak>(&s)) {
      Frames(static_cast<int64_t>(k->duration_s / kFramePeriod_s / options_.thermal_speedup), tag);
    }
    if (const auto* j = std::get_if<hil::F4Jump>(&s)) {
      if (jumps_left[i] < 0) jumps_left[i] = j->count;
      if (jumps_left[i] > 0) {
        --jumps_left[i];
        i = static_cast<size_t>(j->to_step - 1);
        continue;
      }
      jumps_left[i] = -1;
    }
    if (std::holds_alternative<hil::F4End>(s)) break;
    ++i;
  }
}

void ImuRunSimulator::Run(const calib::Sequence& sequence, const ImuRowSink& sink) {
  sink_ = &sink;
  const calib::ExecutionPlan plan = calib::ExpandSequence(sequence, calib::SequenceLimits{});
  const calib::ThermalProfileStep* profile = nullptr;
  for (const calib::PlannedAction& planned : plan.actions) {
    step_ = static_cast<int>(planned.step);
    const calib::Action& a = planned.action;
    if (const auto* m = std::get_if<calib::MountOrientation>(&a)) orientation_ = m->orientation;
    if (const auto* r = std::get_if<calib::SetTableRate>(&a)) rate_dps_ = r->rate_dps;
    if (std::holds_alternative<calib::StopTable>(a)) rate_dps_ = 0.0;
    if (const auto* c = std::get_if<calib::SetChamberSetPoint>(&a)) air_c_ = c->temp_c;
    if (const auto* w = std::get_if<calib::WaitChamberSoak>(&a)) {
      if (options_.soak_frames) {
        Frames(*options_.soak_frames, 0);
      } else {
        for (auto& unit : units_) unit->SoakWithoutFrames(air_c_, w->soak_s);
        const auto frames = static_cast<int64_t>(std::llround(w->soak_s / kFramePeriod_s));
        seq_ += static_cast<uint32_t>(frames);
        t_s_ += static_cast<double>(frames) * kFramePeriod_s;
      }
    }
    if (const auto* acquire = std::get_if<calib::AcquirePackets>(&a)) {
      Frames(options_.settle_frames, 0);
      Frames(acquire->packets, planned.tag);
    }
    if (const auto* d = std::get_if<calib::DownloadProfile>(&a)) profile = &d->profile;
    if (std::holds_alternative<calib::RunProfileLogging>(a) && profile)
      RunProfile(*profile, planned.tag);
  }
  sink_ = nullptr;
}

}  // namespace adahrs::proving
