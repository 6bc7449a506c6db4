#include "hil/codecs/modbus_rtu.h"

#include <stdexcept>
#include <string>
#include <utility>

#include <boost/crc.hpp>

namespace adahrs::hil::modbus {
namespace {

void PutU16(std::vector<uint8_t>& out, uint16_t value) {
  out.push_back(static_cast<uint8_t>(value >> 8));
  out.push_back(static_cast<uint8_t>(value & 0xFF));
}

uint16_t GetU16(std::span<const uint8_t> bytes, size_t at) {
  return static_cast<uint16_t>((bytes[at] << 8) | bytes[at + 1]);
}

void CheckCount(uint8_t function, size_t count) {
  const size_t max = function == kReadHoldingRegisters ? kMaxReadCount : kMaxWriteCount;
  if (count < 1 || count > max) {
    throw std::invalid_argument("Modbus FC " + std::to_string(function) + ": register count " +
                                std::to_string(count) + " outside 1.." + std::to_string(max));
  }
}

[[noreturn]] void Unsupported(uint8_t function) {
  throw std::invalid_argument("Modbus: unsupported function code " + std::to_string(function));
}

// The request fields in one place; the builders below fill them for one function code each.
Request MakeRequest(uint8_t address,
                    uint8_t function,
                    uint16_t start_register,
                    uint16_t count,
                    std::vector<uint16_t> values) {
  return {.address = address,
          .function = function,
          .start_register = start_register,
          .count = count,
          .values = std::move(values)};
}

// How a CRC-checked frame fits the length its function code gives (`expected`, -1 for a code the
// codec does not know): kOk, kIllegalFunction or kMalformed.
DecodeStatus LengthStatus(int expected, size_t frame_bytes) {
  if (expected < 0) return DecodeStatus::kIllegalFunction;
  return static_cast<size_t>(expected) == frame_bytes ? DecodeStatus::kOk
                                                      : DecodeStatus::kMalformed;
}

}  // namespace

Request ReadRequest(uint8_t address, uint16_t start_register, uint16_t count) {
  return MakeRequest(address, kReadHoldingRegisters, start_register, count, {});
}

Request WriteSingleRequest(uint8_t address, uint16_t reg, uint16_t value) {
  return MakeRequest(address, kWriteSingleRegister, reg, 1, {value});
}

Request WriteMultipleRequest(uint8_t address,
                             uint16_t start_register,
                             std::vector<uint16_t> values) {
  const auto count = static_cast<uint16_t>(values.size());  // before the values are moved
  return MakeRequest(address, kWriteMultipleRegisters, start_register, count, std::move(values));
}

Response ExceptionResponse(uint8_t address, uint8_t function, ExceptionCode code) {
  Response response;
  response.address = address;
  response.function = function;
  response.is_exception = true;
  response.exception = code;
  return response;
}

uint16_t Crc16(std::span<const uint8_t> bytes) {
  // Polynomial 0x8005 reflected in and out (0xA001 in the spec's reflected form), init 0xFFFF.
  boost::crc_optimal<16, 0x8005, 0xFFFF, 0, true, true> crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

void AppendCrc(std::vector<uint8_t>& frame) {
  const uint16_t crc = Crc16(frame);
  frame.push_back(static_cast<uint8_t>(crc & 0xFF));
  frame.push_back(static_cast<uint8_t>(crc >> 8));
}

bool CrcMatches(std::span<const uint8_t> frame) {
  if (frame.size() < 4) return false;
  const uint16_t crc = Crc16(frame.first(frame.size() - 2));
  return frame[frame.size() - 2] == (crc & 0xFF) && frame[frame.size() - 1] == (crc >> 8);
}

std::vector<uint8_t> EncodeRequest(const Request& request) {
  std::vector<uint8_t> frame{request.address, request.function};
  PutU16(frame, request.start_register);
  switch (request.function) {
    case kReadHoldingRegisters:
      CheckCount(request.function, request.count);
      PutU16(frame, request.count);
      break;
    case kWriteSingleRegister:
      if (request.values.size() != 1) {
        throw std::invalid_argument("Modbus FC 6: exactly one value expected, got " +
                                    std::to_string(request.values.size()));
      }
      PutU16(frame, request.values[0]);
      break;
    case kWriteMultipleRegisters:
      CheckCount(request.function, request.values.size());
      PutU16(frame, static_cast<uint16_t>(request.values.size()));
      frame.push_back(static_cast<uint8_t>(2 * request.values.size()));
      for (uint16_t value : request.values) PutU16(frame, value);
      break;
    default:
      Unsupported(request.function);
  }
  AppendCrc(frame);
  return frame;
}

std::vector<uint8_t> EncodeResponse(const Response& response) {
  std::vector<uint8_t> frame{response.address};
  if (response.is_exception) {
    frame.push_back(static_cast<uint8_t>(response.function | kExceptionFlag));
    frame.push_back(static_cast<uint8_t>(response.exception));
    AppendCrc(frame);
    return frame;
  }
  frame.push_back(response.function);
  switch (response.function) {
    case kReadHoldingRegisters:
      CheckCount(response.function, response.values.size());
      frame.push_back(static_cast<uint8_t>(2 * response.values.size()));
      for (uint16_t value : response.values) PutU16(frame, value);
      break;
    case kWriteSingleRegister:
      if (response.values.size() != 1) {
        throw std::invalid_argument("Modbus FC 6 reply: exactly one value expected, got " +
                                    std::to_string(response.values.size()));
      }
      PutU16(frame, response.start_register);
      PutU16(frame, response.values[0]);
      break;
    case kWriteMultipleRegisters:
      CheckCount(response.function, response.count);
      PutU16(frame, response.start_register);
      PutU16(frame, response.count);
      break;
    default:
      Unsupported(response.function);
  }
  AppendCrc(frame);
  return frame;
}

int RequestFrameLength(std::span<const uint8_t> prefix) {
  if (prefix.size() < 2) return 0;
  switch (prefix[1]) {
    case kReadHoldingRegisters:
    case kWriteSingleRegister:
      return 8;  // address, function, 2 × 16-bit fields, CRC
    case kWriteMultipleRegisters:
      // address, function, start, count, byte count, data, CRC
      return prefix.size() < 7 ? 0 : 9 + prefix[6];
    default:
      return -1;
  }
}

int ResponseFrameLength(std::span<const uint8_t> prefix) {
  if (prefix.size() < 2) return 0;
  if (prefix[1] & kExceptionFlag) return 5;  // address, function | 0x80, code, CRC
  switch (prefix[1]) {
    case kReadHoldingRegisters:
      return prefix.size() < 3 ? 0 : 5 + prefix[2];
    case kWriteSingleRegister:
    case kWriteMultipleRegisters:
      return 8;
    default:
      return -1;
  }
}

DecodedRequest DecodeRequest(std::span<const uint8_t> frame) {
  DecodedRequest out;
  if (!CrcMatches(frame)) return out;
  Request& request = out.request;
  request.address = frame[0];
  request.function = frame[1];
  out.status = LengthStatus(RequestFrameLength(frame), frame.size());
  if (out.status != DecodeStatus::kOk) return out;
  request.start_register = GetU16(frame, 2);
  switch (request.function) {
    case kReadHoldingRegisters:
      request.count = GetU16(frame, 4);
      if (request.count < 1 || request.count > kMaxReadCount) {
        out.status = DecodeStatus::kIllegalDataValue;
      }
      break;
    case kWriteSingleRegister:
      request.count = 1;
      request.values = {GetU16(frame, 4)};
      break;
    default: {  // kWriteMultipleRegisters
      request.count = GetU16(frame, 4);
      const size_t byte_count = frame[6];
      if (request.count < 1 || request.count > kMaxWriteCount || byte_count != 2u * request.count) {
        out.status = DecodeStatus::kIllegalDataValue;
        break;
      }
      for (size_t i = 0; i < request.count; ++i) request.values.push_back(GetU16(frame, 7 + 2 * i));
      break;
    }
  }
  return out;
}

DecodedResponse DecodeResponse(std::span<const uint8_t> frame) {
  DecodedResponse out;
  if (!CrcMatches(frame)) return out;
  Response& response = out.response;
  response.address = frame[0];
  response.function = static_cast<uint8_t>(frame[1] & ~kExceptionFlag);
  out.status = LengthStatus(ResponseFrameLength(frame), frame.size());
  if (out.status != DecodeStatus::kOk) return out;
  if (frame[1] & kExceptionFlag) {
    response.is_exception = true;
    response.exception = static_cast<ExceptionCode>(frame[2]);
    return out;
  }
  switch (response.function) {
    case kReadHoldingRegisters:
      response.count = static_cast<uint16_t>(frame[2] / 2);
      if (frame[2] % 2 != 0 || response.count < 1 || response.count > kMaxReadCount) {
        out.status = DecodeStatus::kMalformed;
        break;
      }
      for (size_t i = 0; i < response.count; ++i) {
        response.values.push_back(GetU16(frame, 3 + 2 * i));
      }
      break;
    case kWriteSingleRegister:
      response.start_register = GetU16(frame, 2);
      response.count = 1;
      response.values = {GetU16(frame, 4)};
      break;
    default:  // kWriteMultipleRegisters
      response.start_register = GetU16(frame, 2);
      response.count = GetU16(frame, 4);
      if (response.count < 1 || response.count > kMaxWriteCount) {
        out.status = DecodeStatus::kMalformed;
      }
      break;
  }
  return out;
}

}  // namespace adahrs::hil::modbus
