// Modbus RTU framing (pure bytes ↔ messages; no file descriptors, no time) for the function codes
// the Watlow F4 speaks: 03 read holding registers, 06 write single register, 16 write multiple
// registers, and exception replies. Both directions: the virtual F4 (rig_sim/watlow_f4_device.h)
// decodes requests and encodes replies; a client can encode requests and decode replies.
//
// Frame = slave address (1 byte) | PDU | CRC-16/MODBUS, low byte first.
// Sources: Modbus over Serial Line v1.02 §2.5.1 (RTU frame, 3.5-character silence delimits frames)
// and §6.2.2 (CRC: init 0xFFFF, reflected polynomial 0xA001); Modbus Application Protocol v1.1b3
// §6.3 (FC 03: quantity 1..125), §6.6 (FC 06), §6.12 (FC 16: quantity 1..123, byte count = 2·N),
// §7 (exception reply: function | 0x80, one exception code). Watlow F4 use of FC 03/06/16 and
// exceptions 01/02/03: shared/protocols.md §2.1 (DRV / DOC).
// Register addresses are PDU addresses as printed in the F4 manual (no 40001 offset, §2.1 DRV).
// Left out: broadcast (address 0) semantics beyond decoding, other function codes, ASCII mode.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace adahrs::hil::modbus {

inline constexpr uint8_t kReadHoldingRegisters = 0x03;
inline constexpr uint8_t kWriteSingleRegister = 0x06;
inline constexpr uint8_t kWriteMultipleRegisters = 0x10;
inline constexpr uint8_t kExceptionFlag = 0x80;

inline constexpr uint16_t kMaxReadCount = 125;   // Application Protocol §6.3
inline constexpr uint16_t kMaxWriteCount = 123;  // Application Protocol §6.12
/// Longest RTU frame (Serial Line §2.5.1).
inline constexpr size_t kMaxFrameBytes = 256;

enum class ExceptionCode : uint8_t {
  kIllegalFunction = 0x01,
  kIllegalDataAddress = 0x02,
  kIllegalDataValue = 0x03,
};

/// A request PDU with its slave address. FC 03: `start_register`, `count`. FC 06:
/// `start_register`, `values` = {value}. FC 16: `start_register`, `values` (count = size).
struct Request {
  uint8_t address = 1;
  uint8_t function = kReadHoldingRegisters;
  uint16_t start_register = 0;
  uint16_t count = 0;
  std::vector<uint16_t> values;
};

/// A reply. For FC 03 `values` holds the registers read; for FC 06 `start_register`/`values[0]`
/// echo the write; for FC 16 `start_register`/`count` echo it; for an exception `exception` is set.
struct Response {
  uint8_t address = 1;
  uint8_t function = kReadHoldingRegisters;  // without the exception flag
  bool is_exception = false;
  ExceptionCode exception = ExceptionCode::kIllegalFunction;
  uint16_t start_register = 0;
  uint16_t count = 0;
  std::vector<uint16_t> values;
};

/// Requests built field by field for the three function codes.
Request ReadRequest(uint8_t address, uint16_t start_register, uint16_t count);
Request WriteSingleRequest(uint8_t address, uint16_t reg, uint16_t value);
Request WriteMultipleRequest(uint8_t address,
                             uint16_t start_register,
                             std::vector<uint16_t> values);
/// An exception reply to `function` from `address`.
Response ExceptionResponse(uint8_t address, uint8_t function, ExceptionCode code);

/// CRC-16/MODBUS of `bytes` (check value of "123456789" is 0x4B37), computed with Boost.CRC
/// (crc_optimal<16, 0x8005, 0xFFFF, 0, true, true>) as the unit protocol's HostCrc16 is.
uint16_t Crc16(std::span<const uint8_t> bytes);

/// Appends the CRC (low byte first) to `frame`.
void AppendCrc(std::vector<uint8_t>& frame);

/// True when `frame` is at least 4 bytes long and ends with the CRC of the bytes before it.
bool CrcMatches(std::span<const uint8_t> frame);

/// Encodes a request frame. Throws std::invalid_argument for an unsupported function code or a
/// count/values size outside the protocol's limits.
std::vector<uint8_t> EncodeRequest(const Request& request);

/// Encodes a reply frame (normal or exception). Throws std::invalid_argument like EncodeRequest.
std::vector<uint8_t> EncodeResponse(const Response& response);

/// Length of the request frame that starts `prefix`, from its function code (and, for FC 16, its
/// byte count); 0 when more bytes are needed to know; -1 when the function code is not one of
/// 03/06/16 (the frame can then only be delimited by the line's silence).
int RequestFrameLength(std::span<const uint8_t> prefix);

/// Length of the reply frame that starts `prefix` (normal or exception), as RequestFrameLength.
int ResponseFrameLength(std::span<const uint8_t> prefix);

enum class DecodeStatus {
  kOk,
  kBadCrc,            ///< too short or CRC mismatch: the frame is ignored (no reply)
  kIllegalFunction,   ///< CRC good, function code not supported → exception 01
  kIllegalDataValue,  ///< CRC good, count/byte count outside the protocol → exception 03
  kMalformed,         ///< CRC good, length inconsistent with the function code → ignored
};

struct DecodedRequest {
  DecodeStatus status = DecodeStatus::kBadCrc;
  Request request;  ///< address and function are valid for every status but kBadCrc
};

/// Decodes one complete request frame (server side).
DecodedRequest DecodeRequest(std::span<const uint8_t> frame);

struct DecodedResponse {
  DecodeStatus status = DecodeStatus::kBadCrc;
  Response response;
};

/// Decodes one complete reply frame (client side). kIllegalFunction here means a function code
/// the codec does not know; kMalformed a length that does not fit the function code, or a register
/// count outside the protocol's (FC 03 byte count 2..250 and even, FC 16 echoed count 1..123).
DecodedResponse DecodeResponse(std::span<const uint8_t> frame);

}  // namespace adahrs::hil::modbus
