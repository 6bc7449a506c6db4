// Wire constants of the unit serial protocol: the contract in docs/unit-protocol.md (section
// numbers below refer to it). Shared by the unit firmware (target/) and the PC side.
//
// Frame (§2): sync 0xA5 0x5A | length | type | sequence | tag | payload[length] | CRC-16 (LE).
// `length` counts payload bytes only; the CRC (CRC-16/CCITT-FALSE, crc16.h) covers every byte
// from `length` to the end of the payload. Multi-byte fields are little-endian.
// Not modelled here: baud rate and UART framing (8N1 at 115,200 baud is assumed in the doc, the
// byte stream itself is all the codec sees).
#ifndef ADAHRS_FW_UNIT_PROTOCOL_H
#define ADAHRS_FW_UNIT_PROTOCOL_H

#include <stdint.h>

#include "compensated_frame.h"

#ifdef __cplusplus
extern "C" {
#endif

/// First and second sync byte (§2).
#define FW_SYNC_BYTE0 ((uint8_t)0xA5u)
#define FW_SYNC_BYTE1 ((uint8_t)0x5Au)
/// Bytes before the payload: sync (2), length, type, sequence, tag.
#define FW_FRAME_HEADER_BYTES 6u
/// Bytes after the payload: the CRC-16.
#define FW_FRAME_TRAILER_BYTES 2u
/// Largest payload any packet type may carry (the length field is one byte).
#define FW_MAX_PAYLOAD_BYTES 250u
#define FW_MAX_FRAME_BYTES (FW_FRAME_HEADER_BYTES + FW_MAX_PAYLOAD_BYTES + FW_FRAME_TRAILER_BYTES)

/// Packet types (§2.2).
typedef enum {
  FW_PACKET_IMU_DATA = 0x01,             ///< unit -> PC, 100 Hz IMU data (§4)
  FW_PACKET_ADS_DATA = 0x02,             ///< unit -> PC, 100 Hz air-data (§5)
  FW_PACKET_MAINTENANCE_REQUEST = 0x20,  ///< PC -> unit (§6)
  FW_PACKET_MAINTENANCE_RESPONSE = 0x21  ///< unit -> PC, ACK or NAK of one request (§6)
} FwPacketType;

// Output modes: FwImuMode and FwAdsMode (compensated_frame.h); their values are the mode byte on
// the wire (§4.1, §5.1).

/// Which product a unit is; selects the mode set and the constant blocks (§6.3).
typedef enum { FW_UNIT_IMU = 0x01, FW_UNIT_ADS = 0x02 } FwUnitKind;

/// IMU data payload (§4): 6 x (T1, T2) uint16, 3 gyro int32, 3 temperature uint16, mode byte,
/// then, unless the mode is raw, 9 int32 compensated values and a uint16 of status flags.
#define FW_IMU_RAW_PAYLOAD_BYTES ((6u * 2u * 2u) + (3u * 4u) + (3u * 2u) + 1u)
#define FW_IMU_COMPENSATED_PAYLOAD_BYTES (FW_IMU_RAW_PAYLOAD_BYTES + (9u * 4u) + 2u)
/// ADS data payload (§5): ps, pt, ps bridge, pt bridge, oat int32, mode byte, then, unless the
/// mode is raw, 2 int32 (altitude, airspeed) and a uint16 of status flags.
#define FW_ADS_RAW_PAYLOAD_BYTES ((5u * 4u) + 1u)
#define FW_ADS_COMPENSATED_PAYLOAD_BYTES (FW_ADS_RAW_PAYLOAD_BYTES + (2u * 4u) + 2u)

/// Maintenance commands (§6.2): first payload byte of a request, echoed in the response.
typedef enum {
  FW_CMD_NONE = 0x00,  ///< used only in a response to a frame that failed its CRC
  FW_CMD_SET_MODE = 0x01,
  FW_CMD_SET_TAG = 0x02,
  FW_CMD_WRITE_BLOCK = 0x03,
  FW_CMD_READ_BLOCK = 0x04,
  FW_CMD_COMMIT = 0x05,
  FW_CMD_IDENTIFY = 0x06,
  FW_CMD_RESET = 0x07,
  FW_CMD_READ_COUNTERS = 0x08
} FwMaintenanceCommand;

/// Second byte of every response (§6.4): 0 is ACK, anything else a NAK with its reason.
typedef enum {
  FW_RESULT_ACK = 0x00,
  FW_RESULT_BAD_CRC = 0x01,     ///< request frame failed its CRC
  FW_RESULT_BAD_LENGTH = 0x02,  ///< request payload length wrong for the command
  FW_RESULT_UNKNOWN_COMMAND = 0x03,
  FW_RESULT_BAD_ARGUMENT = 0x04,        ///< mode not defined for this unit kind, or similar
  FW_RESULT_NO_VALID_CONSTANTS = 0x05,  ///< calibrated mode refused: no valid committed constants
  FW_RESULT_UNKNOWN_BLOCK = 0x06,
  FW_RESULT_BLOCK_WRONG_LENGTH = 0x07,  ///< word count wrong for the block
  FW_RESULT_CONSTANT_OUT_OF_RANGE = 0x08,
  FW_RESULT_CONSTANT_OVERFLOW = 0x09,     ///< block would overflow its fixed-point format
  FW_RESULT_INCOMPLETE_CONSTANTS = 0x0A,  ///< commit refused: not every block holds valid ones
  FW_RESULT_FLASH_ERROR = 0x0B            ///< stored image does not fit the flash page
} FwResultCode;
/// One past the largest result code; sizes the per-code counters.
#define FW_RESULT_CODE_COUNT 0x0Cu

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_UNIT_PROTOCOL_H
