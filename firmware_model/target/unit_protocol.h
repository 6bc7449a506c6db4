// Wire constants of the unit serial protocol: the contract in docs/unit-protocol.md (section
// numbers below refer to it). Shared by the unit firmware (target/) and the PC side.
//
// Frame (§2): sync 0xA5 0x5A | length | type | sequence | tag | payload[length] | CRC-16 (LE).
// `length` counts payload bytes only; the CRC (CRC-16/CCITT-FALSE, crc16.h) covers every byte
// from `length` to the end of the payload. Multi-byte fields are little-endian.
// Not modelled here: baud rate and UART framing (8N1 at 115,200 baud is assumed in the doc, the
// byte stream itself is all the codec sees).
#pragma once

#include <cstdint>

#include "firmware_model/target/compensated_frame.h"

namespace adahrs::firmware_model {

/// First and second sync byte (§2).
inline constexpr uint8_t kSyncByte0 = 0xA5;
inline constexpr uint8_t kSyncByte1 = 0x5A;
/// Bytes before the payload: sync (2), length, type, sequence, tag.
inline constexpr uint16_t kFrameHeaderBytes = 6;
/// Bytes after the payload: the CRC-16.
inline constexpr uint16_t kFrameTrailerBytes = 2;
/// Largest payload any packet type may carry (the length field is one byte).
inline constexpr uint16_t kMaxPayloadBytes = 250;
inline constexpr uint16_t kMaxFrameBytes =
    kFrameHeaderBytes + kMaxPayloadBytes + kFrameTrailerBytes;

/// Packet types (§2.2).
enum class PacketType : uint8_t {
  kImuData = 0x01,              ///< unit -> PC, 100 Hz IMU data (§4)
  kAdsData = 0x02,              ///< unit -> PC, 100 Hz air-data (§5)
  kMaintenanceRequest = 0x20,   ///< PC -> unit (§6)
  kMaintenanceResponse = 0x21,  ///< unit -> PC, ACK or NAK of one request (§6)
};

// Output modes: ImuCompensationMode and AdsCompensationMode (compensated_frame.h); their values
// are the mode byte on the wire (§4.1, §5.1).

/// Which product a unit is; selects the mode set and the constant blocks (§6.3).
enum class UnitKind : uint8_t {
  kImu = 0x01,
  kAds = 0x02,
};

/// IMU data payload (§4): 6 x (T1, T2) uint16, 3 gyro int32, 3 temperature uint16, mode byte,
/// then, unless the mode is raw, 9 int32 compensated values and a uint16 of status flags.
inline constexpr uint8_t kImuRawPayloadBytes = 6 * 2 * 2 + 3 * 4 + 3 * 2 + 1;
inline constexpr uint8_t kImuCompensatedPayloadBytes = kImuRawPayloadBytes + 9 * 4 + 2;
/// ADS data payload (§5): ps, pt, ps bridge, pt bridge, oat int32, mode byte, then, unless the
/// mode is raw, 2 int32 (altitude, airspeed) and a uint16 of status flags.
inline constexpr uint8_t kAdsRawPayloadBytes = 5 * 4 + 1;
inline constexpr uint8_t kAdsCompensatedPayloadBytes = kAdsRawPayloadBytes + 2 * 4 + 2;

/// Maintenance commands (§6.2): first payload byte of a request, echoed in the response.
enum class MaintenanceCommand : uint8_t {
  kNone = 0x00,  ///< used only in a response to a frame that failed its CRC
  kSetMode = 0x01,
  kSetTag = 0x02,
  kWriteBlock = 0x03,
  kReadBlock = 0x04,
  kCommit = 0x05,
  kIdentify = 0x06,
  kReset = 0x07,
  kReadCounters = 0x08,
};

/// Second byte of every response (§6.4): 0 is ACK, anything else a NAK with its reason.
enum class ResultCode : uint8_t {
  kAck = 0x00,
  kBadCrc = 0x01,     ///< request frame failed its CRC
  kBadLength = 0x02,  ///< request payload length wrong for the command
  kUnknownCommand = 0x03,
  kBadArgument = 0x04,       ///< mode not defined for this unit kind, or similar
  kNoValidConstants = 0x05,  ///< calibrated mode refused: no valid committed constants
  kUnknownBlock = 0x06,
  kBlockWrongLength = 0x07,  ///< word count wrong for the block
  kConstantOutOfRange = 0x08,
  kConstantOverflow = 0x09,     ///< block would overflow its fixed-point format
  kIncompleteConstants = 0x0A,  ///< commit refused: not every block holds valid constants
  kFlashError = 0x0B,           ///< stored image does not fit the flash page
};
/// One past the largest result code; sizes the per-code counters.
inline constexpr uint8_t kResultCodeCount = 0x0C;

}  // namespace adahrs::firmware_model
