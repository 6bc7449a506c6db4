// One ADS unit (the ADAHRS air-data board) on its serial port, as the rig serves it: the unit's
// physics (sensor_sim::AdsUnit) under the rig's conditions and the unit's firmware (maintenance
// port, fixed-point surface compensator, data packets) on the simulated clock; port behaviour in
// unit_device.h.
//
// Stimulus per sample, from RigEnvironment: ps_pa and qc_pa as the air data test set delivers
// them to the ports, ads_chamber_air_c around the board and at the OAT probe (the probe sits in
// the bench chamber with the unit).
// Firmware per sample: the firmware's own sample function (adahrs_fw_ads_sample,
// target/adahrs_fw.h) on the handler: in surface mode the compensator with the handler's RAM
// constants and the hysteresis operators' memory, which starts fresh whenever the unit enters the
// surface mode or is powered (RAM is lost unpowered; the firmware does not keep it in flash); the
// packet carries the handler's next sequence number and current TAG (§5).
// Left out: pneumatic lag between the test set and the ports (the ADTS model slews), leaks.
#pragma once

#include <cstdint>
#include <string>

#include "firmware_model/unit_firmware.h"
#include "rig_sim/unit_device.h"
#include "sensor_sim/ads_unit.h"

namespace adahrs::rig_sim {

struct AdsUnitDeviceConfig {
  std::string role = "ads1";
  uint32_t serial_number = 1;        ///< reported by IDENTIFY
  sensor_sim::AdsUnitParams params;  ///< the unit's drawn parameters (its truth)
  uint64_t noise_seed = 1;
  int baud = 115200;
  double initial_air_c = 25.0;  ///< die temperatures at power-on
};

class AdsUnitDevice : public UnitDevice {
 public:
  /// Throws std::invalid_argument naming the value if the line rate is invalid.
  explicit AdsUnitDevice(const AdsUnitDeviceConfig& config);

  const sensor_sim::AdsUnit& unit() const { return unit_; }

 protected:
  uint16_t Acquire(double sample_s,
                   const RigEnvironment& env,
                   bool encode,
                   firmware_model::MaintenanceHandler& handler,
                   uint8_t* frame,
                   uint16_t capacity) override;

 private:
  sensor_sim::AdsUnit unit_;
  AdahrsFwAdsState firmware_ads_{};  ///< the hysteresis operators; zero: fresh, not compensating
};

}  // namespace adahrs::rig_sim
