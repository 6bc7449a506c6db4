#include "hil/codecs/modbus_rtu.h"

#include <string_view>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::hil::modbus {
namespace {

using Bytes = std::vector<uint8_t>;

std::span<const uint8_t> AsBytes(std::string_view text) {
  return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

TEST(ModbusRtuCrc, MatchesTheCatalogueCheckValue) {
  // CRC-16/MODBUS check value over ASCII "123456789" (Williams/"CRC RevEng" catalogue): 0x4B37.
  EXPECT_EQ(Crc16(AsBytes("123456789")), 0x4B37);
  // Same catalogue: the register starts at 0xFFFF with no final XOR (so the CRC of nothing is
  // 0xFFFF), and a frame followed by its CRC, low byte first, leaves the residue 0x0000.
  EXPECT_EQ(Crc16({}), 0xFFFF);
  const Bytes framed = {0x01, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC5, 0xCD};
  EXPECT_EQ(Crc16(framed), 0x0000);
}

TEST(ModbusRtuCrc, MatchesPublishedRequestFrames) {
  // The request examples of the Simply Modbus function-code pages (slave 0x11):
  // FC 03 read 3 from 0x006B: 11 03 00 6B 00 03 76 87; FC 06 write 3 to 0x0001:
  // 11 06 00 01 00 03 9A 9B; FC 16 write {0x000A, 0x0102} from 0x0001: ... 01 02 C6 F0.
  EXPECT_EQ(EncodeRequest(ReadRequest(0x11, 0x006B, 3)),
            (Bytes{0x11, 0x03, 0x00, 0x6B, 0x00, 0x03, 0x76, 0x87}));
  EXPECT_EQ(EncodeRequest(WriteSingleRequest(0x11, 0x0001, 0x0003)),
            (Bytes{0x11, 0x06, 0x00, 0x01, 0x00, 0x03, 0x9A, 0x9B}));
  EXPECT_EQ(EncodeRequest(WriteMultipleRequest(0x11, 0x0001, {0x000A, 0x0102})),
            (Bytes{0x11, 0x10, 0x00, 0x01, 0x00, 0x02, 0x04, 0x00, 0x0A, 0x01, 0x02, 0xC6, 0xF0}));
}

TEST(ModbusRtuRequest, EncodesTheTextbookReadFrame) {
  // Read 10 holding registers from 0 at slave 1: the frame printed in the Modbus RTU literature
  // (e.g. Simply Modbus "Function 03" page): 01 03 00 00 00 0A C5 CD.
  EXPECT_EQ(EncodeRequest(ReadRequest(1, 0, 10)),
            (Bytes{0x01, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC5, 0xCD}));
  // Exception 02 to FC 03 from slave 1 (same literature): 01 83 02 C0 F1.
  const Response exception =
      ExceptionResponse(1, kReadHoldingRegisters, ExceptionCode::kIllegalDataAddress);
  EXPECT_EQ(EncodeResponse(exception), (Bytes{0x01, 0x83, 0x02, 0xC0, 0xF1}));
}

TEST(ModbusRtuRequest, RoundTripsEveryFunctionCode) {
  const Request requests[] = {
      ReadRequest(1, 100, 1),
      WriteSingleRequest(7, 300, 0xFE70),
      WriteMultipleRequest(1, 4000, {1, 2, 5}),
  };
  for (const Request& request : requests) {
    const Bytes frame = EncodeRequest(request);
    EXPECT_EQ(RequestFrameLength(frame), static_cast<int>(frame.size()));
    const DecodedRequest decoded = DecodeRequest(frame);
    ASSERT_EQ(decoded.status, DecodeStatus::kOk);
    EXPECT_EQ(decoded.request.address, request.address);
    EXPECT_EQ(decoded.request.function, request.function);
    EXPECT_EQ(decoded.request.start_register, request.start_register);
    EXPECT_EQ(decoded.request.values, request.values);
  }
}

TEST(ModbusRtuResponse, RoundTripsReadsWritesAndExceptions) {
  Response read;
  read.values = {250, 0xFF9C};
  const Bytes read_frame = EncodeResponse(read);
  // 1 address + 1 function + 1 byte count + 2·2 data + 2 CRC.
  EXPECT_EQ(read_frame.size(), 9u);
  EXPECT_EQ(ResponseFrameLength(read_frame), 9);
  DecodedResponse decoded = DecodeResponse(read_frame);
  ASSERT_EQ(decoded.status, DecodeStatus::kOk);
  EXPECT_EQ(decoded.response.values, read.values);

  Response write;
  write.function = kWriteMultipleRegisters;
  write.start_register = 4001;
  write.count = 2;
  decoded = DecodeResponse(EncodeResponse(write));
  ASSERT_EQ(decoded.status, DecodeStatus::kOk);
  EXPECT_EQ(decoded.response.start_register, 4001);
  EXPECT_EQ(decoded.response.count, 2);

  const Response refused =
      ExceptionResponse(1, kWriteSingleRegister, ExceptionCode::kIllegalDataValue);
  const Bytes refused_frame = EncodeResponse(refused);
  EXPECT_EQ(ResponseFrameLength(refused_frame), 5);
  decoded = DecodeResponse(refused_frame);
  ASSERT_EQ(decoded.status, DecodeStatus::kOk);
  EXPECT_TRUE(decoded.response.is_exception);
  EXPECT_EQ(decoded.response.function, kWriteSingleRegister);
  EXPECT_EQ(decoded.response.exception, ExceptionCode::kIllegalDataValue);
}

TEST(ModbusRtuDecode, RejectsEveryCorruptedCrcAndClassifiesGoodFramesItCannotServe) {
  const Bytes frame = EncodeRequest(ReadRequest(1, 100, 1));
  // Every single-bit error is detected: the generator has the factor (x + 1) and more than one
  // term (Peterson & Brown 1961), so no single flip of the 64 bits passes.
  for (size_t bit = 0; bit < 8 * frame.size(); ++bit) {
    Bytes corrupted = frame;
    corrupted[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_EQ(DecodeRequest(corrupted).status, DecodeStatus::kBadCrc) << "bit " << bit;
  }
  EXPECT_EQ(DecodeRequest(Bytes{0x01, 0x03}).status, DecodeStatus::kBadCrc);

  Bytes input_registers{0x01, 0x04, 0x00, 0x64, 0x00, 0x01};  // FC 04: not an F4 function
  AppendCrc(input_registers);
  EXPECT_EQ(RequestFrameLength(input_registers), -1);
  EXPECT_EQ(DecodeRequest(input_registers).status, DecodeStatus::kIllegalFunction);

  Bytes zero_count{0x01, 0x03, 0x00, 0x64, 0x00, 0x00};  // quantity 0 (§6.3: 1..125) → 03
  AppendCrc(zero_count);
  EXPECT_EQ(DecodeRequest(zero_count).status, DecodeStatus::kIllegalDataValue);
  Bytes too_many{0x01, 0x03, 0x00, 0x64, 0x00, 126};
  AppendCrc(too_many);
  EXPECT_EQ(DecodeRequest(too_many).status, DecodeStatus::kIllegalDataValue);

  Bytes byte_count_mismatch{0x01, 0x10, 0x0F, 0xA0, 0x00, 0x02, 0x02, 0x00, 0x01};  // 2 regs, 2 B
  AppendCrc(byte_count_mismatch);
  EXPECT_EQ(DecodeRequest(byte_count_mismatch).status, DecodeStatus::kIllegalDataValue);

  Bytes nine_bytes_fc06{0x01, 0x06, 0x01, 0x2C, 0x00, 0xFA, 0x00};  // one byte too many
  AppendCrc(nine_bytes_fc06);
  EXPECT_EQ(DecodeRequest(nine_bytes_fc06).status, DecodeStatus::kMalformed);
}

TEST(ModbusRtuFraming, LengthIsKnownOnceTheHeaderHasArrived) {
  const Bytes fc16 = EncodeRequest(WriteMultipleRequest(1, 3500, {'A', 'B', 'C'}));
  const std::span<const uint8_t> all(fc16);
  EXPECT_EQ(RequestFrameLength(all.first(1)), 0);
  EXPECT_EQ(RequestFrameLength(all.first(6)), 0);  // byte count not yet here
  EXPECT_EQ(RequestFrameLength(all.first(7)), 9 + 6);
  EXPECT_EQ(ResponseFrameLength(Bytes{0x01, 0x03}), 0);
  EXPECT_EQ(ResponseFrameLength(Bytes{0x01, 0x03, 0x04}), 9);
}

Bytes WithCrc(Bytes frame) {
  AppendCrc(frame);
  return frame;
}

TEST(ModbusRtuDecode, RepliesWithRegisterCountsOutsideTheProtocolAreMalformed) {
  // FC 03 byte count 0 and 252 (126 registers), FC 16 echoing 0 and 124 registers: each frame's
  // length fits its header, none is a reply the protocol allows (nor one EncodeResponse writes).
  Bytes too_many_read = {0x01, 0x03, 252};
  too_many_read.resize(3 + 252, 0x00);
  for (const Bytes& frame : {WithCrc({0x01, 0x03, 0x00}),
                             WithCrc(too_many_read),
                             WithCrc({0x01, 0x10, 0x00, 0x64, 0x00, 0x00}),
                             WithCrc({0x01, 0x10, 0x00, 0x64, 0x00, 124})}) {
    EXPECT_EQ(DecodeResponse(frame).status, DecodeStatus::kMalformed) << frame.size() << " bytes";
  }
  EXPECT_EQ(DecodeResponse(WithCrc({0x01, 0x03, 0x02, 0x00, 0xFA})).status, DecodeStatus::kOk);
  EXPECT_EQ(DecodeResponse(WithCrc({0x01, 0x10, 0x00, 0x64, 0x00, 123})).status, DecodeStatus::kOk);
}

TEST(ModbusRtuEncode, RefusesCountsOutsideTheProtocolNamingThem) {
  try {
    EncodeRequest(ReadRequest(1, 0, 126));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("count 126 outside 1..125"));
  }
  Request input_registers = ReadRequest(1, 0, 1);
  input_registers.function = 0x04;
  EXPECT_THROW(EncodeRequest(input_registers), std::invalid_argument);
  Request no_value = WriteSingleRequest(1, 300, 0);
  no_value.values.clear();
  EXPECT_THROW(EncodeRequest(no_value), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::hil::modbus
