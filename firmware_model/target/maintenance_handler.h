// The unit side of the maintenance port (docs/unit-protocol.md §6-7): decodes request frames,
// executes commands against the unit's RAM state and emulated flash, and answers every request
// with an ACK or a NAK carrying a reason code. State: output mode, step TAG, the RAM constant set
// (FwImuConstants or FwAdsConstants), which of its blocks hold valid constants, whether a valid
// committed image backs them, and the data-packet sequence counter. Commands: SET_MODE, SET_TAG,
// WRITE_BLOCK, READ_BLOCK, COMMIT, IDENTIFY, RESET, READ_COUNTERS. Rules (§6.3): a refused request
// never changes state; calibrated modes need committed constants; COMMIT needs every block of the
// set; RESET is a simulated power cycle; a bad CRC gets a NAK, header errors are only counted.
// Fixed-width integers, fixed buffers (one static struct), status returns: builds for the dsPIC.
// Rules, result codes and the flash image: docs/unit-protocol.md ("6.3 Rules", "6.4 Result codes",
// "7. Emulated flash image").
// Not modelled: UART timing, the real unit's watchdog and brown-out behaviour, and concurrency with
// the 100 Hz acquisition interrupt (on the target, mode/TAG/constant updates must be applied
// between frames).
#ifndef ADAHRS_FW_MAINTENANCE_HANDLER_H
#define ADAHRS_FW_MAINTENANCE_HANDLER_H

#include <stdbool.h>
#include <stdint.h>

#include "ads_constants.h"
#include "compensated_frame.h"
#include "flash_store.h"
#include "imu_constants.h"
#include "packet_codec.h"
#include "unit_protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Factory identity reported by IDENTIFY.
typedef struct {
  FwUnitKind kind;
  uint32_t serial_number;
  uint8_t firmware_major;
  uint8_t firmware_minor;
  uint8_t firmware_patch;
} FwUnitIdentity;

typedef struct {
  uint32_t requests_acked;
  uint32_t requests_naked;
  uint32_t naks_by_code[FW_RESULT_CODE_COUNT];  ///< index = FwResultCode value; [0] stays 0
} FwHandlerCounters;

/// Result of fw_maintenance_receive.
typedef struct {
  uint16_t consumed_bytes;  ///< bytes taken from the offered chunk
  uint16_t response_bytes;  ///< bytes of the response frame written, 0 if none
} FwPortResult;

/// The unit's maintenance state. Read its fields; change it only through the functions below.
typedef struct {
  FwUnitIdentity identity;
  FwFlashStore* flash;  ///< the non-volatile store (not owned)
  FwPacketDecoder decoder;
  FwImuConstants imu_constants;  ///< the RAM constant set of an IMU unit
  FwAdsConstants ads_constants;  ///< the RAM constant set of an ADS unit
  uint32_t blocks_valid_mask;  ///< bit i: block at index i of the unit's set holds valid constants
  bool constants_valid;        ///< the RAM constants come from, or were committed to, a valid image
  uint16_t constants_version;
  uint16_t constants_crc;
  uint8_t mode;  ///< FwImuMode or FwAdsMode value
  uint8_t tag;
  uint8_t data_sequence;
  FwHandlerCounters counters;
  FwFrame frame;                       ///< request being handled
  uint8_t data[FW_MAX_PAYLOAD_BYTES];  ///< ACK data of the response being built
  uint8_t data_length;
  int16_t image_words[FW_FLASH_MAX_PAYLOAD_WORDS];  ///< flash image being built or read
} FwMaintenanceHandler;

/// A unit that has just been powered on with `flash` as its non-volatile store (not owned; must
/// outlive the handler): loads and verifies the committed constants.
void fw_maintenance_init(FwMaintenanceHandler* handler,
                         const FwUnitIdentity* identity,
                         FwFlashStore* flash);

/// Takes received bytes until one response is produced or the chunk is used up. `response` must
/// hold FW_MAX_FRAME_BYTES. Call again with the rest of the chunk while response_bytes is
/// non-zero.
FwPortResult fw_maintenance_receive(FwMaintenanceHandler* handler,
                                    const uint8_t* bytes,
                                    uint16_t count,
                                    uint8_t* response,
                                    uint16_t response_capacity);

/// Executes one CRC-checked request frame and writes the response frame; returns its length
/// (0 if `frame` is not a request or `response_capacity` is below FW_MAX_FRAME_BYTES).
uint16_t fw_maintenance_handle_request(FwMaintenanceHandler* handler,
                                       const FwFrame* frame,
                                       uint8_t* response,
                                       uint16_t response_capacity);

/// What WRITE_BLOCK does with a block's words (the block written into the RAM set and marked
/// valid), for firmware that loads a block without a request frame: ACK, or the NAK code.
FwResultCode fw_maintenance_write_block(FwMaintenanceHandler* handler,
                                        uint8_t block_id,
                                        const int16_t* words,
                                        uint8_t count);

/// Simulated power cycle (the RESET command does the same).
void fw_maintenance_power_cycle(FwMaintenanceHandler* handler);

/// Sequence number for the next data packet; increments, wrapping from 255 to 0.
uint8_t fw_maintenance_take_data_sequence(FwMaintenanceHandler* handler);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_MAINTENANCE_HANDLER_H
