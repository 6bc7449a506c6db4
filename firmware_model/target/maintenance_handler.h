// The unit side of the maintenance port (docs/unit-protocol.md §6-7): decodes request frames,
// executes commands against the unit's RAM state and emulated flash, and answers every request
// with an ACK or a NAK carrying a reason code.
//
// State: output mode, step TAG, the RAM constant set (ImuConstants or AdsConstants, per unit
// kind), which of its blocks hold valid constants, whether a valid committed image backs them,
// and the data-packet sequence counter. Commands: SET_MODE, SET_TAG, WRITE_BLOCK, READ_BLOCK,
// COMMIT, IDENTIFY, RESET, READ_COUNTERS.
// Rules (§6.3): a refused request never changes state (only counters move); calibrated modes are
// refused unless valid constants are committed; COMMIT is refused until every block of the set has
// been written (or loaded from flash) since power-on; RESET is a simulated power cycle: RAM
// constants are replaced by the committed image (uncommitted writes are lost), mode returns to raw,
// TAG and sequence to 0, counters to 0. A request frame that fails its CRC is answered with a NAK
// (command NONE, the sequence byte as received); header errors (unknown type, impossible length)
// are only counted, as nothing in such a frame can be trusted.
// Fixed-width integers, fixed buffers, status returns: builds for the dsPIC.
// Not modelled: UART timing, the real unit's watchdog and brown-out behaviour, and concurrency with
// the 100 Hz acquisition interrupt (on the target, mode/TAG/constant updates must be applied
// between frames).
#pragma once

#include <cstdint>

#include "firmware_model/target/ads_constants.h"
#include "firmware_model/target/compensated_frame.h"
#include "firmware_model/target/flash_store.h"
#include "firmware_model/target/imu_constants.h"
#include "firmware_model/target/packet_codec.h"
#include "firmware_model/target/unit_protocol.h"

namespace adahrs::firmware_model {

/// Factory identity reported by IDENTIFY.
struct UnitIdentity {
  UnitKind kind;
  uint32_t serial_number;
  uint8_t firmware_major;
  uint8_t firmware_minor;
  uint8_t firmware_patch;
};

struct HandlerCounters {
  uint32_t requests_acked;
  uint32_t requests_naked;
  uint32_t naks_by_code[kResultCodeCount];  ///< index = ResultCode value; [0] stays 0
};

/// Result of MaintenanceHandler::Receive.
struct PortResult {
  uint16_t consumed_bytes;  ///< bytes taken from the offered chunk
  uint16_t response_bytes;  ///< bytes of the response frame written, 0 if none
};

class MaintenanceHandler {
 public:
  /// A unit that has just been powered on with `flash` as its non-volatile store (not owned; must
  /// outlive the handler).
  MaintenanceHandler(const UnitIdentity& identity, FlashStore* flash);

  /// Takes received bytes until one response is produced or the chunk is used up. `response` must
  /// hold kMaxFrameBytes. Call again with the rest of the chunk while response_bytes is non-zero.
  PortResult Receive(const uint8_t* bytes,
                     uint16_t count,
                     uint8_t* response,
                     uint16_t response_capacity);

  /// Executes one CRC-checked request frame and writes the response frame; returns its length
  /// (0 if `frame` is not a request or `response_capacity` is below kMaxFrameBytes).
  uint16_t HandleRequest(const Frame& frame, uint8_t* response, uint16_t response_capacity);

  /// Simulated power cycle (the RESET command does the same).
  void PowerCycle();

  /// Sequence number for the next data packet; increments, wrapping from 255 to 0.
  uint8_t TakeDataSequence();

  UnitKind kind() const { return identity_.kind; }
  ImuCompensationMode imu_mode() const { return static_cast<ImuCompensationMode>(mode_); }
  AdsCompensationMode ads_mode() const { return static_cast<AdsCompensationMode>(mode_); }
  uint8_t tag() const { return tag_; }
  /// True when the RAM constants come from, or have been committed to, a valid flash image.
  bool constants_valid() const { return constants_valid_; }
  uint16_t constants_version() const { return constants_version_; }
  uint16_t constants_crc() const { return constants_crc_; }
  const ImuConstants& imu_constants() const { return imu_constants_; }
  const AdsConstants& ads_constants() const { return ads_constants_; }
  const HandlerCounters& counters() const { return counters_; }
  const DecoderCounters& decoder_counters() const { return decoder_.counters(); }

 private:
  // Each command handler fills data_/data_length_ on ACK and returns the result code.
  ResultCode DoSetMode(const Frame& frame);
  ResultCode DoSetTag(const Frame& frame);
  ResultCode DoWriteBlock(const Frame& frame);
  ResultCode DoReadBlock(const Frame& frame);
  ResultCode DoCommit(const Frame& frame);
  ResultCode DoIdentify(const Frame& frame);
  ResultCode DoReset(const Frame& frame);
  ResultCode DoReadCounters(const Frame& frame);

  uint16_t Respond(uint8_t command,
                   uint8_t sequence,
                   ResultCode result,
                   uint8_t* response,
                   uint16_t response_capacity);
  void LoadCommittedConstants();
  void InitConstants();
  uint8_t BlockCount() const;
  uint8_t BlockIdAt(uint8_t index) const;
  bool BlockIndex(uint8_t block_id, uint8_t* index) const;
  ConstantsStatus WriteBlock(uint8_t block_id, const int16_t* words, uint8_t count);
  ConstantsStatus ReadBlock(uint8_t block_id,
                            int16_t* words,
                            uint8_t capacity,
                            uint8_t* count) const;
  uint32_t AllBlocksMask() const;
  /// True when `mask` holds a set the unit can run: every block for the ADS; for the IMU the
  /// format-2 blocks 0x01..0x0F, and the format-3 blocks 0x10..0x1B all or none.
  bool IsCompleteSet(uint32_t mask) const;

  UnitIdentity identity_;
  FlashStore* flash_;
  PacketDecoder decoder_;
  ImuConstants imu_constants_;
  AdsConstants ads_constants_;
  uint32_t blocks_valid_mask_ = 0;  // bit i: block BlockIdAt(i) holds valid constants
  bool constants_valid_ = false;
  uint16_t constants_version_ = 0;
  uint16_t constants_crc_ = 0;
  uint8_t mode_ = 0;
  uint8_t tag_ = 0;
  uint8_t data_sequence_ = 0;
  HandlerCounters counters_ = {};
  Frame frame_ = {};
  uint8_t data_[kMaxPayloadBytes] = {};  // ACK data of the response being built
  uint8_t data_length_ = 0;
  int16_t image_words_[kFlashMaxPayloadWords] = {};  // flash image being built or read
};

}  // namespace adahrs::firmware_model
