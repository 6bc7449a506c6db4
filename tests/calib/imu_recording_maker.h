// Test helper: makes IMU recordings in-process exactly as the executor writes them (contract C2)
// without a rig: simulated units (sensor_sim::ImuUnit) are driven through a sequence's stimuli —
// fixture orientation, table rate about the up axis, chamber air temperature — and every packet
// is written with hil::RecordingWriter: TAG = the step's TAG while acquiring, 0 while settling
// between acquisitions, the orientation commanded, the chamber's reported temperature (0.1 degC)
// and the table's reported rate (command + 0.004 deg/s, within the C2 limit of 0.01).
// Time is compressed where the physics allows it: target_temperature soaks last `soak_frames`, and
// thermal profile ramps and soaks run `thermal_speedup` times faster than written. That is exact
// for units without die lag (ModelProfile::kNominal); with lag on, the ramps would bias the fit.
// truth/<serial>.json holds each unit's parameters, as the rig writes it.
#pragma once

#include "adahrs_build_paths.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/sequence/sequence.h"
#include "calib/sequence/sequence_json.h"
#include "hil/recording/recording_writer.h"
#include "sensor_sim/imu_unit.h"
#include "common/units.h"

namespace adahrs::calib::testing {

struct MakerOptions {
  int settle_frames = 50;        // > 10 filter time constants (3.2 ms accel, 4 ms gyro)
  int soak_frames = 100;
  double thermal_speedup = 30.0;
  double table_rate_error_dps = 0.004;
  double initial_air_temp_c = 25.0;
};

class ImuRecordingMaker {
 public:
  ImuRecordingMaker(std::vector<sensor_sim::ImuUnitParams> units, double g_local_mps2,
                    uint64_t noise_seed, MakerOptions options = {})
      : params_(std::move(units)), g_local_mps2_(g_local_mps2), options_(options) {
    air_c_ = options_.initial_air_temp_c;
    for (size_t i = 0; i < params_.size(); ++i) {
      units_.push_back(std::make_unique<sensor_sim::ImuUnit>(params_[i], noise_seed + 101 * i, air_c_));
    }
  }

  /// Runs `sequence` and writes `run_dir` (meta.json, imu.csv, ads.csv, truth/).
  void Run(const Sequence& sequence, const std::filesystem::path& run_dir) {
    std::filesystem::remove_all(run_dir);
    hil::RecordingWriter writer(run_dir);
    writer_ = &writer;
    nlohmann::json units = nlohmann::json::array();
    for (size_t i = 0; i < params_.size(); ++i) {
      units.push_back({{"role", "imu" + std::to_string(i + 1)}, {"kind", "imu"},
                       {"serial", params_[i].serial}, {"serial_number", i + 1},
                       {"firmware", "1.0.0"}, {"slot", i + 1}, {"constants_version", 0},
                       {"mode", 0}});
    }
    nlohmann::json meta = {{"run_id", sequence.name},
                           {"started_utc", "2024-05-01T12:00:00Z"},
                           {"status", "complete"},
                           {"sequence", nlohmann::json::parse(SequenceToJson(sequence).dump())},
                           {"sequence_file", sequence.name + ".json"},
                           {"time_base", "pipeline clock seconds since the run started"},
                           {"sample_rate_hz", 100},
                           {"local_gravity_mps2", g_local_mps2_},
                           {"units", units},
                           {"instruments", nlohmann::json::array()},
                           {"rejected_intervals", nlohmann::json::array()}};
    const std::vector<uint8_t> tags = EffectiveTags(sequence);
    for (size_t s = 0; s < sequence.steps.size(); ++s) {
      step_ = static_cast<int>(s);
      RunStep(sequence.steps[s].body, tags[s]);
    }
    writer.WriteMeta(meta);
    writer.Flush(true);
    std::filesystem::create_directories(run_dir / "truth");
    for (const auto& p : params_) std::ofstream(run_dir / "truth" / (p.serial + ".json")) << p.ToJson().dump(2);
    writer_ = nullptr;
  }

 private:
  void Frames(int n, uint8_t tag) {
    for (int i = 0; i < n; ++i) {
      sensor_sim::ImuStimulus stimulus;
      Eigen::Vector3d up = Eigen::Vector3d::Zero();
      if (orientation_ != 0) {
        up[orientation_ / 10 - 1] = orientation_ % 10 == 1 ? 1.0 : -1.0;
      }
      stimulus.f_B_g = up * common::Mps2ToG(g_local_mps2_);
      stimulus.w_B_dps = up * rate_dps_;
      stimulus.air_temp_c = air_c_;
      for (size_t u = 0; u < units_.size(); ++u) {
        const sensor_sim::ImuRawFrame f = units_[u]->Step(stimulus);
        hil::ImuRecordRow row;
        row.t_s = t_s_;
        row.unit = params_[u].serial;
        row.seq = seq_ & 0xFF;
        row.step = step_;
        row.tag = tag;
        row.orientation = orientation_;
        row.chamber_c = std::round(air_c_ * 10.0) / 10.0;
        row.table_rate_dps = rate_dps_ == 0.0 ? 0.0 : rate_dps_ + options_.table_rate_error_dps;
        for (int ch = 0; ch < 6; ++ch) {
          row.accel_ticks[2 * ch] = f.accel[ch].t1_cnt;
          row.accel_ticks[2 * ch + 1] = f.accel[ch].t2_cnt;
        }
        for (int g = 0; g < 3; ++g) {
          row.gyro_cnt[g] = f.gyro_cnt[g];
          row.temp_cnt[g] = f.temp_cnt[g];
        }
        writer_->Append(row);
      }
      ++seq_;
      t_s_ += 0.01;
    }
  }

  void Ramp(double target_c, double rate_c_per_min, uint8_t tag) {
    const double step_c = rate_c_per_min / 60.0 * 0.01 * options_.thermal_speedup;
    while (std::abs(target_c - air_c_) > step_c) {
      air_c_ += target_c > air_c_ ? step_c : -step_c;
      Frames(1, tag);
    }
    air_c_ = target_c;
  }

  void RunStep(const StepBody& body, uint8_t tag) {
    if (const auto* a = std::get_if<AccelStep>(&body)) {
      orientation_ = a->orientation;
      rate_dps_ = 0.0;
      Frames(options_.settle_frames, 0);
      Frames(static_cast<int>(a->packets), tag);
    } else if (const auto* g = std::get_if<GyroStep>(&body)) {
      orientation_ = g->orientation;
      for (double r : GyroRates_dps(*g)) {
        rate_dps_ = r;
        Frames(options_.settle_frames, 0);
        Frames(static_cast<int>(g->packets), tag);
      }
      rate_dps_ = 0.0;
    } else if (const auto* c = std::get_if<CrossAxisStep>(&body)) {
      for (int o : kCrossAxisOrientations) {
        orientation_ = o;
        for (double r : {0.0, c->rate_dps}) {
          rate_dps_ = r;
          Frames(options_.settle_frames, 0);
          Frames(static_cast<int>(c->packets), tag);
        }
      }
      rate_dps_ = 0.0;
    } else if (const auto* t = std::get_if<TargetTemperatureStep>(&body)) {
      air_c_ = t->target_c;
      Frames(options_.soak_frames, 0);
    } else if (const auto* p = std::get_if<ThermalProfileStep>(&body)) {
      for (const F4ProfileStep& s : p->steps) {
        if (const auto* r = std::get_if<F4RampRate>(&s)) Ramp(r->target_c, r->rate_c_per_min, tag);
        if (const auto* k = std::get_if<F4Soak>(&s)) {
          Frames(static_cast<int>(k->duration_s * 100.0 / options_.thermal_speedup), tag);
        }
      }
    }
  }

  std::vector<sensor_sim::ImuUnitParams> params_;
  std::vector<std::unique_ptr<sensor_sim::ImuUnit>> units_;
  double g_local_mps2_;
  MakerOptions options_;
  hil::RecordingWriter* writer_ = nullptr;
  double air_c_ = 25.0;
  double rate_dps_ = 0.0;
  int orientation_ = 0;
  int step_ = 0;
  uint32_t seq_ = 0;
  double t_s_ = 0.0;
};

/// A shipped sequence (calib/sequences/<name>.json) with every acquisition's packet count set to
/// `packets` (short recordings for tests).
inline Sequence ShippedSequence(const std::string& name, int64_t packets) {
  Sequence s = SequenceFromJson(
      common::ParamReader::LoadFile(std::string(ADAHRS_SOURCE_DIR) + "/calib/sequences/" + name + ".json"),
      name);
  for (Step& step : s.steps) {
    if (auto* a = std::get_if<AccelStep>(&step.body)) a->packets = packets;
    if (auto* g = std::get_if<GyroStep>(&step.body)) g->packets = packets;
    if (auto* c = std::get_if<CrossAxisStep>(&step.body)) c->packets = packets;
  }
  return s;
}

}  // namespace adahrs::calib::testing
