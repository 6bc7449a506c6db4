#include "rig_sim/ads_unit_device.h"

#include "firmware_model/unit_firmware.h"

namespace adahrs::rig_sim {

namespace fm = firmware_model;

AdsUnitDevice::AdsUnitDevice(const AdsUnitDeviceConfig& config)
    : UnitDevice(config.role,
                 {fm::UnitKind::kAds,
                  config.serial_number,
                  kSimulatedFirmwareMajor,
                  kSimulatedFirmwareMinor,
                  kSimulatedFirmwarePatch},
                 config.baud),
      unit_(config.params, config.noise_seed, config.initial_air_c) {}

uint16_t AdsUnitDevice::Acquire(double,
                                const RigEnvironment& env,
                                bool encode,
                                fm::MaintenanceHandler& handler,
                                uint8_t* frame,
                                uint16_t capacity) {
  sensor_sim::AdsStimulus stimulus;
  stimulus.ps_pa = env.ps_pa;
  stimulus.qc_pa = env.qc_pa;
  stimulus.air_temp_c = env.ads_chamber_air_c;
  stimulus.oat_c = env.ads_chamber_air_c;
  const sensor_sim::AdsRawFrame measured = unit_.Step(stimulus);
  if (!encode) {
    adahrs_fw_ads_power_lost(&firmware_ads_);  // unpowered: the operators' RAM is lost
    return 0;
  }
  const FwAdsRawFrame raw = {measured.ps_cnt,
                             measured.pt_cnt,
                             measured.ps_temp_cnt,
                             measured.pt_temp_cnt,
                             measured.oat_cnt};
  fm::DspEngine engine;
  return adahrs_fw_ads_sample(handler.c(), &firmware_ads_, engine.c(), &raw, frame, capacity);
}

}  // namespace adahrs::rig_sim
