#include "hil/codecs/unit_protocol_client.h"

#include <algorithm>
#include <array>

#include <boost/crc.hpp>

#include "firmware_model/unit_firmware.h"

namespace adahrs::hil {
namespace {

std::string Hex2(unsigned value) {
  constexpr char kDigits[] = "0123456789abcdef";
  return std::string{kDigits[(value >> 4) & 0xFu], kDigits[value & 0xFu]};
}

// Response data lengths (docs/unit-protocol.md §6.2).
constexpr size_t kIdentifyDataBytes = 15;
constexpr size_t kCommitDataBytes = 4;
constexpr size_t kCountersDataBytes = 7 * 4;
// A write request is command, block id, word count, then the words.
constexpr size_t kWriteBlockHeaderBytes = 3;
constexpr size_t kMaxBlockWords = (firmware_model::kMaxPayloadBytes - kWriteBlockHeaderBytes) / 2;

std::string CommandName(firmware_model::MaintenanceCommand command) {
  switch (command) {
    case firmware_model::MaintenanceCommand::kNone:
      return "NONE";
    case firmware_model::MaintenanceCommand::kSetMode:
      return "SET_MODE";
    case firmware_model::MaintenanceCommand::kSetTag:
      return "SET_TAG";
    case firmware_model::MaintenanceCommand::kWriteBlock:
      return "WRITE_BLOCK";
    case firmware_model::MaintenanceCommand::kReadBlock:
      return "READ_BLOCK";
    case firmware_model::MaintenanceCommand::kCommit:
      return "COMMIT";
    case firmware_model::MaintenanceCommand::kIdentify:
      return "IDENTIFY";
    case firmware_model::MaintenanceCommand::kReset:
      return "RESET";
    case firmware_model::MaintenanceCommand::kReadCounters:
      return "READ_COUNTERS";
  }
  return "command 0x" + Hex2(static_cast<unsigned>(command));
}

// Checks that `response` is an ACK of `expected` carrying `data_bytes` bytes (any length if 0).
void ExpectAck(const MaintenanceResponse& response,
               firmware_model::MaintenanceCommand expected,
               size_t data_bytes) {
  if (response.command != expected) {
    throw ProtocolError("expected a response to " + CommandName(expected) + ", got one to " +
                        CommandName(response.command) + " (sequence " +
                        std::to_string(response.sequence) + ")");
  }
  if (response.result != firmware_model::ResultCode::kAck) {
    throw ProtocolError(CommandName(expected) +
                        " refused by the unit: " + ResultCodeName(response.result) + " (sequence " +
                        std::to_string(response.sequence) + ")");
  }
  if (data_bytes != 0 && response.data.size() != data_bytes) {
    throw ProtocolError(CommandName(expected) + " response carries " +
                        std::to_string(response.data.size()) + " data bytes, expected " +
                        std::to_string(data_bytes));
  }
}

void ExpectFrameType(const firmware_model::Frame& frame,
                     firmware_model::PacketType type,
                     const char* what) {
  if (frame.type != static_cast<uint8_t>(type)) {
    throw ProtocolError(std::string("expected ") + what + " (type 0x" +
                        Hex2(static_cast<unsigned>(type)) + "), got packet type 0x" +
                        Hex2(frame.type));
  }
}

}  // namespace

uint16_t HostCrc16(std::span<const uint8_t> bytes) {
  boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false> crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

std::vector<uint8_t> BuildFrame(uint8_t type,
                                uint8_t sequence,
                                uint8_t tag,
                                std::span<const uint8_t> payload) {
  if (payload.size() > firmware_model::kMaxPayloadBytes) {
    throw ProtocolError("payload of " + std::to_string(payload.size()) +
                        " bytes exceeds the protocol maximum of " +
                        std::to_string(firmware_model::kMaxPayloadBytes));
  }
  std::vector<uint8_t> frame;
  frame.reserve(firmware_model::kFrameHeaderBytes + payload.size() +
                firmware_model::kFrameTrailerBytes);
  for (const uint8_t header_byte : {firmware_model::kSyncByte0,
                                    firmware_model::kSyncByte1,
                                    static_cast<uint8_t>(payload.size()),
                                    type,
                                    sequence,
                                    tag}) {
    frame.push_back(header_byte);
  }
  for (const uint8_t payload_byte : payload) {
    frame.push_back(payload_byte);
  }
  // The CRC covers everything after the sync pair.
  const uint16_t crc = HostCrc16(std::span<const uint8_t>(frame).subspan(2));
  frame.push_back(static_cast<uint8_t>(crc & 0xFFu));
  frame.push_back(static_cast<uint8_t>(crc >> 8));
  return frame;
}

std::string ResultCodeName(firmware_model::ResultCode code) {
  switch (code) {
    case firmware_model::ResultCode::kAck:
      return "ACK";
    case firmware_model::ResultCode::kBadCrc:
      return "NAK bad CRC";
    case firmware_model::ResultCode::kBadLength:
      return "NAK bad length";
    case firmware_model::ResultCode::kUnknownCommand:
      return "NAK unknown command";
    case firmware_model::ResultCode::kBadArgument:
      return "NAK bad argument";
    case firmware_model::ResultCode::kNoValidConstants:
      return "NAK no valid constants";
    case firmware_model::ResultCode::kUnknownBlock:
      return "NAK unknown block";
    case firmware_model::ResultCode::kBlockWrongLength:
      return "NAK block wrong length";
    case firmware_model::ResultCode::kConstantOutOfRange:
      return "NAK constant out of range";
    case firmware_model::ResultCode::kConstantOverflow:
      return "NAK constant overflows fixed-point format";
    case firmware_model::ResultCode::kIncompleteConstants:
      return "NAK incomplete constants";
    case firmware_model::ResultCode::kFlashError:
      return "NAK flash error";
  }
  return "NAK code 0x" + Hex2(static_cast<unsigned>(code));
}

std::string HexTrace(std::span<const uint8_t> bytes) {
  std::string out;
  for (size_t i = 0; i < bytes.size(); ++i) {
    if (i != 0) {
      out.push_back(' ');
    }
    out.append(Hex2(bytes[i]));
  }
  return out;
}

std::vector<firmware_model::Frame> StreamReader::Push(std::span<const uint8_t> bytes) {
  std::vector<firmware_model::Frame> frames;
  size_t offset = 0;
  firmware_model::Frame frame;
  while (true) {
    // Feed takes at most 65,535 bytes per call; the loop hands over the rest.
    const size_t chunk = std::min<size_t>(bytes.size() - offset, 0xFFFF);
    const firmware_model::DecodeResult result =
        decoder_.Feed(bytes.data() + offset, static_cast<uint16_t>(chunk), &frame);
    offset += result.consumed_bytes;
    if (result.event == firmware_model::DecodeEvent::kFrame) {
      frames.push_back(frame);
    } else if (result.event == firmware_model::DecodeEvent::kNeedMoreBytes &&
               offset == bytes.size()) {
      return frames;
    }
  }
}

std::vector<uint8_t> UnitProtocolClient::Request(uint8_t command,
                                                 std::span<const uint8_t> arguments) {
  std::vector<uint8_t> payload = {command};
  payload.insert(payload.end(), arguments.begin(), arguments.end());
  const uint8_t sequence = next_sequence_++;
  return BuildFrame(
      static_cast<uint8_t>(firmware_model::PacketType::kMaintenanceRequest), sequence, 0, payload);
}

std::vector<uint8_t> UnitProtocolClient::SetImuMode(firmware_model::ImuCompensationMode mode) {
  const std::array<uint8_t, 1> arguments = {static_cast<uint8_t>(mode)};
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kSetMode), arguments);
}

std::vector<uint8_t> UnitProtocolClient::SetAdsMode(firmware_model::AdsCompensationMode mode) {
  const std::array<uint8_t, 1> arguments = {static_cast<uint8_t>(mode)};
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kSetMode), arguments);
}

std::vector<uint8_t> UnitProtocolClient::SetTag(uint8_t tag) {
  const std::array<uint8_t, 1> arguments = {tag};
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kSetTag), arguments);
}

std::vector<uint8_t> UnitProtocolClient::WriteBlock(uint8_t block_id,
                                                    std::span<const int16_t> words) {
  if (words.size() > kMaxBlockWords) {
    throw ProtocolError("constant block " + std::to_string(block_id) + " has " +
                        std::to_string(words.size()) + " words; one request carries at most " +
                        std::to_string(kMaxBlockWords));
  }
  std::vector<uint8_t> arguments = {block_id, static_cast<uint8_t>(words.size())};
  for (const int16_t word : words) {
    uint8_t bytes[2];
    firmware_model::PutI16Le(bytes, word);
    arguments.push_back(bytes[0]);
    arguments.push_back(bytes[1]);
  }
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kWriteBlock), arguments);
}

std::vector<uint8_t> UnitProtocolClient::ReadBlock(uint8_t block_id) {
  const std::array<uint8_t, 1> arguments = {block_id};
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kReadBlock), arguments);
}

std::vector<uint8_t> UnitProtocolClient::Commit() {
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kCommit), {});
}

std::vector<uint8_t> UnitProtocolClient::Identify() {
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kIdentify), {});
}

std::vector<uint8_t> UnitProtocolClient::Reset() {
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kReset), {});
}

std::vector<uint8_t> UnitProtocolClient::ReadCounters() {
  return Request(static_cast<uint8_t>(firmware_model::MaintenanceCommand::kReadCounters), {});
}

MaintenanceResponse ParseMaintenanceResponse(const firmware_model::Frame& frame) {
  ExpectFrameType(
      frame, firmware_model::PacketType::kMaintenanceResponse, "a maintenance response");
  if (frame.payload_length < 2) {
    throw ProtocolError("maintenance response payload of " + std::to_string(frame.payload_length) +
                        " bytes; at least 2 expected");
  }
  MaintenanceResponse response;
  response.sequence = frame.sequence;
  response.command = static_cast<firmware_model::MaintenanceCommand>(frame.payload[0]);
  response.result = static_cast<firmware_model::ResultCode>(frame.payload[1]);
  response.data.assign(frame.payload + 2, frame.payload + frame.payload_length);
  return response;
}

IdentifyInfo ParseIdentify(const MaintenanceResponse& response) {
  ExpectAck(response, firmware_model::MaintenanceCommand::kIdentify, kIdentifyDataBytes);
  const uint8_t* d = response.data.data();
  IdentifyInfo info;
  info.unit_kind = static_cast<firmware_model::UnitKind>(d[0]);
  info.serial_number = firmware_model::GetU32Le(d + 1);
  info.firmware_major = d[5];
  info.firmware_minor = d[6];
  info.firmware_patch = d[7];
  info.constants_valid = d[8] != 0;
  info.constants_version = firmware_model::GetU16Le(d + 9);
  info.constants_crc = firmware_model::GetU16Le(d + 11);
  info.mode = d[13];
  info.tag = d[14];
  return info;
}

CommitInfo ParseCommit(const MaintenanceResponse& response) {
  ExpectAck(response, firmware_model::MaintenanceCommand::kCommit, kCommitDataBytes);
  return CommitInfo{firmware_model::GetU16Le(response.data.data()),
                    firmware_model::GetU16Le(response.data.data() + 2)};
}

BlockReadback ParseReadBlock(const MaintenanceResponse& response) {
  ExpectAck(response, firmware_model::MaintenanceCommand::kReadBlock, 0);
  if (response.data.size() < 2 || response.data.size() != 2 + 2 * size_t{response.data[1]}) {
    throw ProtocolError("READ_BLOCK response carries " + std::to_string(response.data.size()) +
                        " data bytes, inconsistent with its word count");
  }
  BlockReadback readback{response.data[0], {}};
  for (size_t i = 0; i < response.data[1]; ++i) {
    readback.words.push_back(firmware_model::GetI16Le(response.data.data() + 2 + 2 * i));
  }
  return readback;
}

UnitCounters ParseCounters(const MaintenanceResponse& response) {
  ExpectAck(response, firmware_model::MaintenanceCommand::kReadCounters, kCountersDataBytes);
  const uint8_t* d = response.data.data();
  UnitCounters counters;
  counters.decoder.frames_ok = firmware_model::GetU32Le(d);
  counters.decoder.bad_crc = firmware_model::GetU32Le(d + 4);
  counters.decoder.bad_length = firmware_model::GetU32Le(d + 8);
  counters.decoder.unknown_type = firmware_model::GetU32Le(d + 12);
  counters.decoder.resync_bytes_skipped = firmware_model::GetU32Le(d + 16);
  counters.requests_acked = firmware_model::GetU32Le(d + 20);
  counters.requests_naked = firmware_model::GetU32Le(d + 24);
  return counters;
}

firmware_model::ImuDataPayload ParseImuData(const firmware_model::Frame& frame) {
  ExpectFrameType(frame, firmware_model::PacketType::kImuData, "an IMU data packet");
  firmware_model::ImuDataPayload data;
  if (!firmware_model::DecodeImuPayload(frame.payload, frame.payload_length, &data)) {
    throw ProtocolError("IMU data payload of " + std::to_string(frame.payload_length) +
                        " bytes is malformed (length must be 43 in raw mode, 81 otherwise, with a "
                        "mode byte 0..3): " +
                        HexTrace({frame.payload, frame.payload_length}));
  }
  return data;
}

firmware_model::AdsDataPayload ParseAdsData(const firmware_model::Frame& frame) {
  ExpectFrameType(frame, firmware_model::PacketType::kAdsData, "an ADS data packet");
  firmware_model::AdsDataPayload data;
  if (!firmware_model::DecodeAdsPayload(frame.payload, frame.payload_length, &data)) {
    throw ProtocolError("ADS data payload of " + std::to_string(frame.payload_length) +
                        " bytes is malformed (length must be 21 in raw mode, 31 otherwise, with a "
                        "mode byte 0..1): " +
                        HexTrace({frame.payload, frame.payload_length}));
  }
  return data;
}

uint32_t SequenceTracker::Observe(uint8_t sequence) {
  uint32_t lost = 0;
  if (has_previous_) {
    lost = static_cast<uint8_t>(sequence - previous_ - 1);
  }
  has_previous_ = true;
  previous_ = sequence;
  lost_total_ += lost;
  return lost;
}

}  // namespace adahrs::hil
