// A calibration run of simulated IMUs in process: the units (sensor_sim::ImuUnit, in lockstep as
// a batch on one fixture) are driven through a sequence's execution plan (ExpandSequence) — the
// fixture orientation, the table rate about the up axis, the chamber air temperature — and every
// packet is handed to a sink as the executor records it: TAG = the step's TAG while acquiring,
// 0 while settling before an acquisition, the orientation commanded, the chamber's reported
// temperature (0.1 degC) and the table's reported rate (command + table_rate_error_dps), each
// column at the resolution a recording writes it.
// Time: 100 frames/s. A chamber set point is reached at once and held for the step's soak; with
// `soak_frames` empty the soak is simulated without frames (the die temperatures advance exactly,
// the sensors' noise processes do not), otherwise as that many settling frames. Thermal profile
// ramps and soaks are logged frame by frame, `thermal_speedup` times faster than written (1: as a
// rig runs them; larger compresses time, exact only for units without die lag).
// Left out: interlock checks (no frames), table acceleration (the rate changes at once and the
// settling frames follow), the chamber's own ramp to a set point, packet loss.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "calib/sequence/sequence.h"
#include "hil/recording/recording_format.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {

struct ImuRunSimulatorOptions {
  int settle_frames = 50;          ///< > 10 filter time constants (3.2 ms accel, 4 ms gyro)
  std::optional<int> soak_frames;  ///< empty: soaks without frames, for the step's soak_s
  double thermal_speedup = 1.0;
  double table_rate_error_dps = 0.004;
  double initial_air_temp_c = 25.0;
};

using ImuRowSink = std::function<void(const hil::ImuRecordRow&)>;

class ImuRunSimulator {
 public:
  /// Powers the units on; unit i draws its noise from `noise_seed + 101 i`.
  ImuRunSimulator(std::vector<sensor_sim::ImuUnitParams> units,
                  double g_local_mps2,
                  uint64_t noise_seed,
                  ImuRunSimulatorOptions options = {});

  /// Runs `sequence` (refused with SequenceError if invalid against the default limits), handing
  /// every packet of every unit to `sink` in time order.
  void Run(const calib::Sequence& sequence, const ImuRowSink& sink);

  const std::vector<sensor_sim::ImuUnitParams>& params() const { return params_; }

 private:
  void Frames(int64_t n, uint8_t tag);
  void Ramp(double target_c, double rate_c_per_min, uint8_t tag);
  void RunProfile(const calib::ThermalProfileStep& profile, uint8_t tag);

  std::vector<sensor_sim::ImuUnitParams> params_;
  std::vector<std::unique_ptr<sensor_sim::ImuUnit>> units_;
  double g_local_mps2_;
  ImuRunSimulatorOptions options_;
  const ImuRowSink* sink_ = nullptr;
  double air_c_ = 25.0;
  double rate_dps_ = 0.0;
  int orientation_ = 0;
  int step_ = 0;
  uint32_t seq_ = 0;
  double t_s_ = 0.0;
};

}  // namespace adahrs::proving
