// The unit firmware's C API: what an MPLAB X project includes to run the compensation on the
// dsPIC. One unit holds a maintenance port (FwMaintenanceHandler: mode, TAG, the RAM constants and
// their validity, backed by the committed flash image), a DSP engine (the cycle model), and for an
// ADS unit the hysteresis operators' memory (AdahrsFwAdsState), all caller-owned fixed-size RAM.
// Entry points: adahrs_fw_power_on (loads the committed constants, verifies their CRC),
// adahrs_fw_receive (maintenance requests in, one response frame out), adahrs_fw_imu_sample /
// adahrs_fw_ads_sample (the 100 Hz sample: raw frame in, compensated in the port's mode, encoded
// as the data packet), adahrs_fw_load_block and adahrs_fw_verify_constants. The compensators
// themselves are fw_imu_compensate and fw_ads_compensate (imu_compensator.h, ads_compensator.h).
// Units: raw frames in counts and timer ticks; outputs as compensated_frame.h says.
// Use, RAM and cycle figures: docs/firmware-compensator.md ("Dropping target/ into an MPLAB X
// project").
// Not modelled: the ISRs themselves, the UART and timer drivers, the NVM driver that would program
// the flash page (flash_store.h models the page in RAM).
#ifndef ADAHRS_FW_H
#define ADAHRS_FW_H

#include <stdbool.h>
#include <stdint.h>

#include "ads_compensator.h"
#include "compensated_frame.h"
#include "dsp_engine.h"
#include "fixed_coeff.h"
#include "flash_store.h"
#include "imu_compensator.h"
#include "maintenance_handler.h"
#include "unit_protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

/// What an ADS unit keeps between frames: the hysteresis operators, live while it compensates
/// (they start fresh whenever compensation starts, and after a power loss).
typedef struct {
  FwAdsHysteresisState hysteresis;
  bool compensating;
} AdahrsFwAdsState;

/// Power-on: the port's state from the committed image in `flash` (not owned), the ADS state
/// (may be NULL for an IMU unit) fresh.
void adahrs_fw_power_on(FwMaintenanceHandler* port,
                        AdahrsFwAdsState* ads,
                        const FwUnitIdentity* identity,
                        FwFlashStore* flash);

/// UART RX: takes received bytes until one response is produced or the chunk is used up
/// (fw_maintenance_receive). `response` holds FW_MAX_FRAME_BYTES.
FwPortResult adahrs_fw_receive(FwMaintenanceHandler* port,
                               const uint8_t* bytes,
                               uint16_t count,
                               uint8_t* response,
                               uint16_t response_capacity);

/// The 100 Hz IMU sample: compensates `raw` in the port's mode (nothing to compute in raw mode)
/// with the engine in the compensator's configuration, and writes the data packet (sequence from
/// the port, its TAG) into `frame`; returns the packet's length, 0 if `capacity` is too small.
/// The engine's counters add up the cycles spent.
uint16_t adahrs_fw_imu_sample(FwMaintenanceHandler* port,
                              FwDspEngine* engine,
                              const FwImuRawFrame* raw,
                              uint8_t* frame,
                              uint16_t capacity);

/// The 100 Hz ADS sample, as adahrs_fw_imu_sample; advances the hysteresis operators in `ads`.
uint16_t adahrs_fw_ads_sample(FwMaintenanceHandler* port,
                              AdahrsFwAdsState* ads,
                              FwDspEngine* engine,
                              const FwAdsRawFrame* raw,
                              uint8_t* frame,
                              uint16_t capacity);

/// The ADS unit lost power: the operators' RAM is gone (the next compensated frame starts fresh).
void adahrs_fw_ads_power_lost(AdahrsFwAdsState* ads);

/// Loads one constants block into the RAM set as WRITE_BLOCK does: FW_RESULT_ACK or the NAK code.
FwResultCode adahrs_fw_load_block(FwMaintenanceHandler* port,
                                  uint8_t block_id,
                                  const int16_t* words,
                                  uint8_t count);

/// The committed image as the port's flash holds it (magic, kind, length, CRC checked); `*valid`
/// tells whether the RAM constants come from, or were committed to, that image.
FwFlashImageInfo adahrs_fw_verify_constants(const FwMaintenanceHandler* port, bool* valid);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_H
