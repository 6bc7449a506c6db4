// PC side of the unit serial protocol (docs/unit-protocol.md): builds maintenance request frames
// and parses responses and data packets into typed results. Pure bytes <-> messages, no I/O; the
// hil drivers wrap it around a transport.
//
// Frames are built here with Boost.CRC (crc_optimal<16, 0x1021, 0xFFFF, 0, false, false>, i.e.
// CRC-16/CCITT-FALSE), independently of the target's table CRC, so the unit's decoder is always
// exercised by a second implementation. Parsing errors (wrong packet type, NAK where data was
// expected, a length that does not match the command) throw ProtocolError naming the command,
// the values seen and the values expected; a NAK itself is data (MaintenanceResponse::result).
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "firmware_model/unit_firmware.h"

namespace adahrs::hil {

class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// CRC-16/CCITT-FALSE by Boost.CRC.
uint16_t HostCrc16(std::span<const uint8_t> bytes);

/// One complete frame (sync to CRC). Throws ProtocolError if the payload exceeds 250 bytes.
std::vector<uint8_t> BuildFrame(uint8_t type,
                                uint8_t sequence,
                                uint8_t tag,
                                std::span<const uint8_t> payload);

/// Human-readable name of a result code ("ACK", "NAK bad CRC", ...), for messages and logs.
std::string ResultCodeName(firmware_model::ResultCode code);

/// Hex dump "a5 5a 02 ..." of a byte sequence, for frame traces and error messages.
std::string HexTrace(std::span<const uint8_t> bytes);

/// Decodes a byte stream chunk by chunk into frames, keeping the decoder's error counters.
class StreamReader {
 public:
  /// Every frame completed by `bytes` (and by bytes held from earlier chunks), in order.
  std::vector<firmware_model::Frame> Push(std::span<const uint8_t> bytes);
  const firmware_model::DecoderCounters& counters() const { return decoder_.counters(); }

 private:
  firmware_model::PacketDecoder decoder_;
};

/// Builds maintenance requests with a wrapping sequence counter (first request has sequence 0).
class UnitProtocolClient {
 public:
  std::vector<uint8_t> SetImuMode(firmware_model::ImuCompensationMode mode);
  std::vector<uint8_t> SetAdsMode(firmware_model::AdsCompensationMode mode);
  std::vector<uint8_t> SetTag(uint8_t tag);
  /// Throws ProtocolError if the block does not fit one request (more than 123 words).
  std::vector<uint8_t> WriteBlock(uint8_t block_id, std::span<const int16_t> words);
  std::vector<uint8_t> ReadBlock(uint8_t block_id);
  std::vector<uint8_t> Commit();
  std::vector<uint8_t> Identify();
  std::vector<uint8_t> Reset();
  std::vector<uint8_t> ReadCounters();
  /// A request with an arbitrary command byte and argument bytes (fault injection, new commands).
  std::vector<uint8_t> Request(uint8_t command, std::span<const uint8_t> arguments);

  /// Sequence number of the most recent request.
  uint8_t last_sequence() const { return static_cast<uint8_t>(next_sequence_ - 1); }

 private:
  uint8_t next_sequence_ = 0;
};

/// A maintenance response: the echoed command, ACK or NAK reason, and the ACK's data bytes.
struct MaintenanceResponse {
  uint8_t sequence;
  firmware_model::MaintenanceCommand command;
  firmware_model::ResultCode result;
  std::vector<uint8_t> data;
};

/// Throws ProtocolError if `frame` is not a maintenance response.
MaintenanceResponse ParseMaintenanceResponse(const firmware_model::Frame& frame);

struct IdentifyInfo {
  firmware_model::UnitKind unit_kind;
  uint32_t serial_number;
  uint8_t firmware_major;
  uint8_t firmware_minor;
  uint8_t firmware_patch;
  bool constants_valid;  ///< a valid committed image was loaded at power-on or committed since
  uint16_t constants_version;  ///< commits so far, 0 if none
  uint16_t constants_crc;      ///< CRC of the committed image, 0 if none
  uint8_t mode;                ///< ImuCompensationMode or AdsCompensationMode value, per unit_kind
  uint8_t tag;
};

struct CommitInfo {
  uint16_t constants_version;
  uint16_t constants_crc;
};

struct BlockReadback {
  uint8_t block_id;
  std::vector<int16_t> words;
};

/// The unit's counters (§6.2 READ_COUNTERS).
struct UnitCounters {
  firmware_model::DecoderCounters decoder;
  uint32_t requests_acked;
  uint32_t requests_naked;
};

// Each parser throws ProtocolError if the response is a NAK, answers another command, or its data
// length is wrong; the message names the command, the result code and the lengths.
IdentifyInfo ParseIdentify(const MaintenanceResponse& response);
CommitInfo ParseCommit(const MaintenanceResponse& response);
BlockReadback ParseReadBlock(const MaintenanceResponse& response);
UnitCounters ParseCounters(const MaintenanceResponse& response);

/// Throws ProtocolError if `frame` is not a well-formed IMU (ADS) data packet.
firmware_model::ImuDataPayload ParseImuData(const firmware_model::Frame& frame);
firmware_model::AdsDataPayload ParseAdsData(const firmware_model::Frame& frame);

/// Loss detection on the wrapping 8-bit data sequence counter: packets missing between
/// consecutive observations, assuming fewer than 256 are lost in a row.
class SequenceTracker {
 public:
  /// Records `sequence`; returns the number of packets lost since the previous one (0 for the
  /// first).
  uint32_t Observe(uint8_t sequence);
  uint64_t lost_total() const { return lost_total_; }

 private:
  bool has_previous_ = false;
  uint8_t previous_ = 0;
  uint64_t lost_total_ = 0;
};

}  // namespace adahrs::hil
