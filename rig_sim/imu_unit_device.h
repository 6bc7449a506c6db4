// One IMU unit (AHR150A-class IM³) on its serial port, as the rig serves it: the unit's physics
// (sensor_sim::ImuUnit) under the rig's conditions and the unit's firmware (maintenance port,
// fixed-point compensator, data packets) on the simulated clock; port behaviour in unit_device.h.
//
// Stimulus per sample, from RigEnvironment (frames in rig_environment.h, docs/frames-and-units.md):
//   f_B_g   = (local_gravity_mps2 / g0) · UpAxis_B(c)     c = imu_orientation[slot]
//   w_B_dps = table_rate_dps · UpAxis_B(c)                 (the unit sits on the table axis)
//   air     = imu_chamber_air_c, supply = supply_v.
// Firmware per sample: the handler's current mode; unless raw, ImuCompensate with the handler's
// RAM constants (the dsPIC's own fixed-point code); the packet carries the handler's next sequence
// number and current TAG (docs/unit-protocol.md §4).
// Left out: centripetal acceleration and table wobble (units on the axis, level table), Earth rate.
#pragma once

#include <cstdint>
#include <string>

#include "rig_sim/unit_device.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::rig_sim {

struct ImuUnitDeviceConfig {
  std::string role = "imu1";
  int slot = 0;                      ///< index into RigEnvironment::imu_orientation, 0…3
  uint32_t serial_number = 1;        ///< reported by IDENTIFY
  sensor_sim::ImuUnitParams params;  ///< the unit's drawn parameters (its truth)
  uint64_t noise_seed = 1;
  int baud = 115200;
  double initial_air_c = 25.0;  ///< die temperatures at power-on
};

class ImuUnitDevice : public UnitDevice {
 public:
  /// Throws std::invalid_argument naming the value if the slot or line rate is invalid.
  explicit ImuUnitDevice(const ImuUnitDeviceConfig& config);

  const sensor_sim::ImuUnit& unit() const { return unit_; }
  int slot() const { return slot_; }

 protected:
  uint16_t Acquire(double sample_s,
                   const RigEnvironment& env,
                   bool encode,
                   firmware_model::MaintenanceHandler& handler,
                   uint8_t* frame,
                   uint16_t capacity) override;

 private:
  int slot_;
  sensor_sim::ImuUnit unit_;
};

}  // namespace adahrs::rig_sim
