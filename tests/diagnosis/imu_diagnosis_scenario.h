// Test helper: the scenario generator of the diagnosis proofs. One simulated IMU
// (sensor_sim::ImuUnit, the truth) is driven through a stimulus program — chamber air ramps and
// soaks, fixture orientations, table rates — and its packets are collected as the calibration
// data LoadImuRuns would give (ImuUnitData), without files: thermal-profile rows labelled by the
// program's own ramp direction, one acquisition per orientation and rate. The diagnoser under test
// never sees this code or the unit's parameters; only the test compares its findings with them.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "calib/imu_calibration/imu_run_data.h"
#include "common/units.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::diagnosis::testing {

class ImuScenario {
 public:
  ImuScenario(const sensor_sim::ImuUnitParams& params,
              uint64_t noise_seed,
              double start_c,
              double g_local_mps2 = 9.80665)
      : unit_(std::make_unique<sensor_sim::ImuUnit>(params, noise_seed, start_c)),
        g_scale_(g_local_mps2 / 9.80665),
        air_c_(start_c) {
    data_.serial = params.serial;
  }

  /// Unrecorded soak: the air steps to `air_c` and the unit sits there at rest.
  void Soak(double air_c, double seconds) {
    NoteChange(air_c);
    air_c_ = air_c;
    for (int i = 0; i < Frames(seconds); ++i) Step(Eigen::Vector3d::Zero(), 0.0, nullptr);
  }

  /// Recorded thermal profile in `orientation`: ramps to each target at `rate_c_per_min`, then
  /// soaks `soak_s` there.
  void ThermalProfile(int orientation,
                      const std::vector<double>& targets_c,
                      double rate_c_per_min,
                      double soak_s) {
    data_.thermal_orientation = orientation;
    const Eigen::Vector3d up = Up(orientation);
    const double step_c = rate_c_per_min / 60.0 * kFrame_s;
    for (double target : targets_c) {
      const calib::ThermalSegment seg =
          target > air_c_ ? calib::ThermalSegment::kUpRamp : calib::ThermalSegment::kDownRamp;
      while (std::abs(target - air_c_) > step_c) {
        NoteChange(target);
        air_c_ += target > air_c_ ? step_c : -step_c;
        ThermalRow(up, seg);
      }
      air_c_ = target;
      for (int i = 0; i < Frames(soak_s); ++i) ThermalRow(up, calib::ThermalSegment::kSoak);
    }
  }

  /// An accelerometer acquisition of `packets` rows after 0.5 s of settling.
  void Accel(int step, int orientation, int packets) {
    Acquire(step, "accel", orientation, 0.0, packets, &data_.accel);
  }

  /// A gyro acquisition at each rate.
  void Gyro(int step, int orientation, const std::vector<double>& rates_dps, int packets) {
    for (double r : rates_dps) Acquire(step, "gyro", orientation, r, packets, &data_.gyro);
  }

  /// Six positions, then rates about each axis (the sensor calibration's shape), at the present
  /// air.
  void SensorCalibration(int first_step, int accel_packets, int gyro_packets) {
    int step = first_step;
    for (int o : {11, 12, 21, 22, 31, 32}) Accel(step++, o, accel_packets);
    for (int o : {11, 21, 31}) Gyro(step++, o, {-150, -100, -50, 50, 100, 150}, gyro_packets);
  }

  /// The rate table's once-per-revolution relative ripple k: the unit turns at
  /// rate (1 + k cos(angle)) while the recording keeps the commanded rate (a rig effect).
  void set_table_rate_ripple(double k) { ripple_ratio_ = k; }

  /// A thermal hysteresis the simulator does not have, written onto the gyro counts: gyro g
  /// reads `half_loop_cnt[g]` more after the air last rose and as much less after it last fell
  /// (nothing before the first change): the up/down loop of a die whose bias keeps a memory of
  /// the direction it was last driven.
  void set_gyro_thermal_hysteresis_cnt(const std::array<double, 3>& half_loop_cnt) {
    hysteresis_cnt_ = half_loop_cnt;
  }

  /// A cross-axis coupling that changes with temperature, which the simulator does not have,
  /// written onto the gyro counts: gyro g reads k(g, j) (T_air - 25 degC) w_B_j more for each
  /// axis j other than its own, k in counts per deg/s per degC.
  void set_gyro_cross_axis_tempco(const Eigen::Matrix3d& k_cnt_per_dps_c) {
    cross_tempco_ = k_cnt_per_dps_c;
  }

  calib::ImuUnitData& data() { return data_; }
  double t_s() const { return t_s_; }

 private:
  static constexpr double kFrame_s = 0.01;
  static int Frames(double seconds) { return static_cast<int>(std::lround(seconds / kFrame_s)); }

  void NoteChange(double target_c) {
    if (target_c > air_c_) sense_ = 1.0;
    if (target_c < air_c_) sense_ = -1.0;
  }

  static Eigen::Vector3d Up(int orientation) {
    const std::array<double, 3> u = calib::UpAxisOf(orientation);
    return {u[0], u[1], u[2]};
  }

  void Step(const Eigen::Vector3d& up, double rate_dps, calib::ImuSample* out) {
    sensor_sim::ImuStimulus s;
    s.f_B_g = up * g_scale_;
    s.w_B_dps = up * rate_dps * (1.0 + ripple_ratio_ * std::cos(table_angle_rad_));
    table_angle_rad_ += rate_dps * kFrame_s * M_PI / 180.0;
    s.air_temp_c = air_c_;
    const sensor_sim::ImuRawFrame f = unit_->Step(s);
    if (out != nullptr) {
      for (int ch = 0; ch < 6; ++ch) {
        out->raw.t1_cnt[ch] = f.accel[ch].t1_cnt;
        out->raw.t2_cnt[ch] = f.accel[ch].t2_cnt;
      }
      for (int g = 0; g < 3; ++g) {
        double extra_cnt = hysteresis_cnt_[g] * sense_;
        for (int j = 0; j < 3; ++j) {
          if (j != g) extra_cnt += cross_tempco_(g, j) * (air_c_ - 25.0) * s.w_B_dps[j];
        }
        out->raw.gyro_cnt[g] = f.gyro_cnt[g] + static_cast<int32_t>(std::lround(extra_cnt));
        out->raw.temp_cnt[g] = f.temp_cnt[g];
      }
      out->t_s = t_s_;
      out->seq = static_cast<uint8_t>(frame_);
      out->chamber_c = std::round(air_c_ * 10.0) / 10.0;
      out->table_rate_dps = rate_dps;
    }
    t_s_ += kFrame_s;
    ++frame_;
  }

  void ThermalRow(const Eigen::Vector3d& up, calib::ThermalSegment seg) {
    calib::ImuSample s;
    Step(up, 0.0, &s);
    data_.thermal.push_back(s);
    data_.thermal_segment.push_back(seg);
  }

  void Acquire(int step,
               const std::string& kind,
               int orientation,
               double rate_dps,
               int packets,
               std::vector<calib::ImuAcquisition>* out) {
    const Eigen::Vector3d up = Up(orientation);
    for (int i = 0; i < 50; ++i) Step(up, rate_dps, nullptr);
    calib::ImuAcquisition a;
    a.run = "scenario";
    a.step = step;
    a.step_kind = kind;
    a.orientation = orientation;
    a.rate_dps = rate_dps;
    for (int i = 0; i < packets; ++i) {
      calib::ImuSample s;
      Step(up, rate_dps, &s);
      a.samples.push_back(s);
    }
    out->push_back(std::move(a));
  }

  std::unique_ptr<sensor_sim::ImuUnit> unit_;
  uint64_t frame_ = 0;  // the packet counter a unit would send
  double ripple_ratio_ = 0.0;
  std::array<double, 3> hysteresis_cnt_{};
  Eigen::Matrix3d cross_tempco_ = Eigen::Matrix3d::Zero();
  double sense_ = 0.0;  // of the air's last change
  double table_angle_rad_ = 0.7;
  double g_scale_;
  double air_c_;
  double t_s_ = 0.0;
  calib::ImuUnitData data_;
};

}  // namespace adahrs::diagnosis::testing
