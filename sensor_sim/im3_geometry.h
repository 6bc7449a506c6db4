// Geometry of the IM³ inertial cube: where each sensor package sits relative to the unit case.
// Nominal mounting (reference-method.md "The unit"): three dual-axis ADXL210E chips give six
// channels az1 ax1 ay1 az2 ax2 ay2, every body axis sensed twice with opposite polarity, with the
// reference's signs; gyros gx gy gz with z_G along +x_B, +y_B, +z_B. Each package carries its own
// small mounting misalignment, a rotation vector θ in B, R_CB = R_CB,nominal · Rot(θ), drawn
// within ±1° per component (ADXL210E alignment ±1°, physics.md §1.1, R; gyros assumed alike, E).
// Frames: B unit case, C_k accelerometer chip k's package (x_C, y_C sensitive), G_k gyro k's
// package (z_G sensitive); f_C = R_CB · f_B. Angles in deg.
// Channel table: docs/frames-and-units.md ("IM³ channels"); parameters: docs/sensor-models.md
// ("IM³ geometry").
// Left out: lever arms (the rig models centripetal terms on the table), flexure of the boards,
// misalignment of the cube within the case.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "common/imu_layout.h"
#include "common/param_reader.h"

namespace adahrs::sensor_sim {

struct Im3Geometry {
  /// Mounting misalignment of each accelerometer chip: small-rotation vector in B, degrees.
  std::array<Eigen::Vector3d, 3> accel_misalignment_deg{
      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  /// Mounting misalignment of each gyro package: small-rotation vector in B, degrees.
  std::array<Eigen::Vector3d, 3> gyro_misalignment_deg{
      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  /// Whether misalignment is applied (a named effect: off gives the nominal mounting).
  bool misalignment = true;

  static Im3Geometry Typical() { return Im3Geometry{}; }
  /// Misalignments drawn within ±1° per component, deterministic per seed.
  static Im3Geometry Draw(uint64_t seed);
  nlohmann::json ToJson() const;
  static Im3Geometry FromJson(const common::ParamReader& reader);
  bool operator==(const Im3Geometry&) const = default;

  /// R_CB of accelerometer chip `chip` (0..2), misalignment included when switched on.
  Eigen::Matrix3d R_CB(int chip) const;
  /// R_GB of gyro `gyro` (0..2), misalignment included when switched on.
  Eigen::Matrix3d R_GB(int gyro) const;
};

}  // namespace adahrs::sensor_sim
