#include "rig_sim/imu_unit_device.h"

#include <stdexcept>

#include "common/units.h"
#include "firmware_model/unit_firmware.h"
#include "rig_sim/fixture_orientation.h"

namespace adahrs::rig_sim {

namespace fm = firmware_model;

namespace {

fm::UnitIdentity ImuIdentity(const ImuUnitDeviceConfig& config) {
  if (config.slot < 0 || config.slot >= kMaxImuUnits) {
    throw std::invalid_argument(config.role + ": IMU slot " + std::to_string(config.slot) +
                                " not in 0…" + std::to_string(kMaxImuUnits - 1));
  }
  return {fm::UnitKind::kImu,
          config.serial_number,
          kSimulatedFirmwareMajor,
          kSimulatedFirmwareMinor,
          kSimulatedFirmwarePatch};
}

}  // namespace

ImuUnitDevice::ImuUnitDevice(const ImuUnitDeviceConfig& config)
    : UnitDevice(config.role, ImuIdentity(config), config.baud),
      slot_(config.slot),
      unit_(config.params, config.noise_seed, config.initial_air_c) {}

uint16_t ImuUnitDevice::Acquire(double,
                                const RigEnvironment& env,
                                bool encode,
                                fm::MaintenanceHandler& handler,
                                uint8_t* frame,
                                uint16_t capacity) {
  const Eigen::Vector3d up_B = UpAxis_B(env.imu_orientation[static_cast<size_t>(slot_)]);
  sensor_sim::ImuStimulus stimulus;
  stimulus.f_B_g = up_B * (env.local_gravity_mps2 / common::kStandardGravity_mps2);
  stimulus.w_B_dps = up_B * env.table_rate_dps;
  stimulus.air_temp_c = env.imu_chamber_air_c;
  stimulus.supply_v = env.supply_v;
  const sensor_sim::ImuRawFrame measured = unit_.Step(stimulus);
  if (!encode) return 0;

  FwImuRawFrame raw{};
  for (int ch = 0; ch < 6; ++ch) {
    raw.t1_cnt[ch] = measured.accel[static_cast<size_t>(ch)].t1_cnt;
    raw.t2_cnt[ch] = measured.accel[static_cast<size_t>(ch)].t2_cnt;
  }
  for (int i = 0; i < 3; ++i) {
    raw.gyro_cnt[i] = measured.gyro_cnt[static_cast<size_t>(i)];
    raw.temp_cnt[i] = measured.temp_cnt[static_cast<size_t>(i)];
  }
  fm::DspEngine engine;
  return adahrs_fw_imu_sample(handler.c(), engine.c(), &raw, frame, capacity);
}

}  // namespace adahrs::rig_sim
