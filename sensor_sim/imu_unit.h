// One simulated IMU unit (AHR150A-class IM³ cube): three ADXL210E dual-axis accelerometer chips
// (six channels az1 ax1 ay1 az2 ax2 ay2), three ADXRS150 gyros (gx gy gz) with their TEMP pins,
// each package with its own mounting misalignment (Im3Geometry) and its own die thermal node.
//
// Input per 100 Hz frame (ImuStimulus): specific force f_B_g and angular rate w_B_dps of the unit
// case B (frames in docs/frames-and-units.md), the air temperature around the unit and its supply
// voltage. Output (ImuRawFrame): what the dsPIC measures — T1/T2 input-capture ticks per
// accelerometer channel, gyro rate counts (16 summed 19-bit conversions) and gyro TEMP counts.
// The accelerometers have no thermometer of their own: the unit's three temperature counts are the
// gyro TEMP pins, so any lag between an accelerometer die and the gyro dies is real physics here.
//
// Left out: lever arms and centripetal acceleration (the rig computes f_B at the unit), vibration,
// the supply's own dynamics (supply_v is an input), electrical cross-talk between channels.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "sensor_sim/adxl210e.h"
#include "sensor_sim/adxrs150.h"
#include "sensor_sim/die_thermal.h"
#include "sensor_sim/im3_geometry.h"
#include "sensor_sim/model_profile.h"

namespace adahrs::sensor_sim {

struct ImuStimulus {
  Eigen::Vector3d f_B_g = Eigen::Vector3d::Zero();    ///< specific force of the case, in B, g
  Eigen::Vector3d w_B_dps = Eigen::Vector3d::Zero();  ///< angular rate of B w.r.t. inertial, in B
  double air_temp_c = 25.0;                           ///< air around the unit
  double supply_v = 5.0;                              ///< sensor supply rail
};

struct ImuRawFrame {
  std::array<Adxl210eCapture, 6> accel{};  ///< az1 ax1 ay1 az2 ax2 ay2
  std::array<int32_t, 3> gyro_cnt{};       ///< gx gy gz
  std::array<uint16_t, 3> temp_cnt{};      ///< TEMP pins of gx gy gz
};

/// Die temperatures after the last step (truth, for diagnosis; a real unit does not report them).
struct ImuDieTemperatures {
  std::array<double, 3> accel_chip_c{};
  std::array<double, 3> gyro_c{};
};

struct ImuUnitParams {
  std::string serial = "IMU-0000";
  double frame_period_s = 0.01;
  std::array<Adxl210eParams, 3> accel_chips;
  std::array<Adxrs150Params, 3> gyros;
  Im3Geometry geometry;
  std::array<DieThermalParams, 3> accel_thermal;
  std::array<DieThermalParams, 3> gyro_thermal;

  /// Every parameter drawn from datasheet distributions, deterministic per seed, with every
  /// effect set for `profile`.
  static ImuUnitParams Draw(const std::string& serial, uint64_t seed, ModelProfile profile);
  /// Switches every sub-model's effects to the profile's set.
  void ApplyProfile(ModelProfile profile);
  /// kSlowBiasWander slows every gyro's flicker poles tenfold and switches its rate random walk on
  /// at three times the drawn one; the other variants leave the IMU as drawn. Apply once, after
  /// Draw (and after ApplyProfile).
  void ApplyVariant(TruthVariant variant);
  nlohmann::json ToJson() const;
  static ImuUnitParams FromJson(const common::ParamReader& reader);
};

class ImuUnit {
 public:
  /// Powers the unit on with every die at `initial_air_temp_c`.
  ImuUnit(const ImuUnitParams& params, uint64_t noise_seed, double initial_air_temp_c);

  /// Advances one frame (params.frame_period_s).
  ImuRawFrame Step(const ImuStimulus& stimulus);

  /// Advances every die through `duration_s` with the air at `air_temp_c`, producing no frame:
  /// the die temperatures are exact (DieThermal::Hold); the sensors' noise processes (bias
  /// instability, rate random walk) do not advance over the interval.
  void SoakWithoutFrames(double air_temp_c, double duration_s);

  const ImuUnitParams& params() const { return params_; }
  const ImuDieTemperatures& die_temperatures() const { return die_; }

 private:
  ImuUnitParams params_;
  std::array<Eigen::Matrix3d, 3> R_CB_;
  std::array<Eigen::Matrix3d, 3> R_GB_;
  std::array<Adxl210e, 3> chips_;
  std::array<Adxrs150, 3> gyros_;
  std::array<DieThermal, 3> accel_die_;
  std::array<DieThermal, 3> gyro_die_;
  ImuDieTemperatures die_;
};

}  // namespace adahrs::sensor_sim
