#include "adahrs_fw.h"

#include <stddef.h>

#include "data_payloads.h"

void adahrs_fw_ads_power_lost(AdahrsFwAdsState* ads) { ads->compensating = false; }

void adahrs_fw_power_on(FwMaintenanceHandler* port,
                        AdahrsFwAdsState* ads,
                        const FwUnitIdentity* identity,
                        FwFlashStore* flash) {
  fw_maintenance_init(port, identity, flash);
  if (ads != NULL) {
    fw_ads_hysteresis_reset(&ads->hysteresis);
    adahrs_fw_ads_power_lost(ads);
  }
}

FwPortResult adahrs_fw_receive(FwMaintenanceHandler* port,
                               const uint8_t* bytes,
                               uint16_t count,
                               uint8_t* response,
                               uint16_t response_capacity) {
  return fw_maintenance_receive(port, bytes, count, response, response_capacity);
}

uint16_t adahrs_fw_imu_sample(FwMaintenanceHandler* port,
                              FwDspEngine* engine,
                              const FwImuRawFrame* raw,
                              uint8_t* frame,
                              uint16_t capacity) {
  FwImuDataPayload payload;
  payload.raw = *raw;
  payload.mode = (FwImuMode)port->mode;
  for (uint8_t i = 0u; i < FW_IMU_OUTPUT_VALUES; ++i) {
    payload.compensated.value[i] = 0;
  }
  payload.compensated.flags = 0u;
  if (payload.mode != FW_IMU_MODE_RAW) {
    fw_imu_compensate(engine, &port->imu_constants, payload.mode, raw, &payload.compensated);
  }
  const uint8_t tag = port->tag;
  return fw_encode_imu_data_frame(
      &payload, fw_maintenance_take_data_sequence(port), tag, frame, capacity);
}

uint16_t adahrs_fw_ads_sample(FwMaintenanceHandler* port,
                              AdahrsFwAdsState* ads,
                              FwDspEngine* engine,
                              const FwAdsRawFrame* raw,
                              uint8_t* frame,
                              uint16_t capacity) {
  FwAdsDataPayload payload;
  payload.raw = *raw;
  payload.mode = (FwAdsMode)port->mode;
  for (uint8_t i = 0u; i < FW_ADS_OUTPUT_VALUES; ++i) {
    payload.compensated.value[i] = 0;
  }
  payload.compensated.flags = 0u;
  if (payload.mode == FW_ADS_MODE_RAW) {
    ads->compensating = false;
  } else {
    if (!ads->compensating) {
      fw_ads_hysteresis_reset(&ads->hysteresis);
    }
    ads->compensating = true;
    fw_ads_compensate(
        engine, &port->ads_constants, payload.mode, raw, &ads->hysteresis, &payload.compensated);
  }
  const uint8_t tag = port->tag;
  return fw_encode_ads_data_frame(
      &payload, fw_maintenance_take_data_sequence(port), tag, frame, capacity);
}

FwResultCode adahrs_fw_load_block(FwMaintenanceHandler* port,
                                  uint8_t block_id,
                                  const int16_t* words,
                                  uint8_t count) {
  return fw_maintenance_write_block(port, block_id, words, count);
}

FwFlashImageInfo adahrs_fw_verify_constants(const FwMaintenanceHandler* port, bool* valid) {
  *valid = port->constants_valid;
  return fw_flash_inspect(port->flash, port->identity.kind);
}
