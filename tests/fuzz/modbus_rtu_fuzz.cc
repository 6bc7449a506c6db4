// Fuzzes the Modbus RTU codec of the Watlow F4 (hil/codecs/modbus_rtu.h), both sides: frame
// lengths of every prefix, then the request and reply decoders on the input as received and with
// its CRC made good (so the fuzzer reaches past the CRC). A frame that decodes kOk must encode
// back to the same bytes. The codec never throws on received bytes; nothing is caught.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "hil/codecs/modbus_rtu.h"

namespace modbus = adahrs::hil::modbus;

namespace {

void Decode(std::span<const uint8_t> frame) {
  const modbus::DecodedRequest request = modbus::DecodeRequest(frame);
  if (request.status == modbus::DecodeStatus::kOk &&
      modbus::EncodeRequest(request.request) != std::vector<uint8_t>(frame.begin(), frame.end())) {
    __builtin_trap();  // a request that does not survive decode -> encode
  }
  const modbus::DecodedResponse response = modbus::DecodeResponse(frame);
  if (response.status == modbus::DecodeStatus::kOk &&
      modbus::EncodeResponse(response.response) !=
          std::vector<uint8_t>(frame.begin(), frame.end())) {
    __builtin_trap();  // a reply that does not survive decode -> encode
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::span<const uint8_t> bytes(data, size);
  for (size_t n = 0; n <= bytes.size() && n <= modbus::kMaxFrameBytes; ++n) {
    (void)modbus::RequestFrameLength(bytes.first(n));
    (void)modbus::ResponseFrameLength(bytes.first(n));
  }
  Decode(bytes);
  if (size >= 2) {
    std::vector<uint8_t> fixed(data, data + size - 2);
    modbus::AppendCrc(fixed);
    Decode(fixed);
  }
  return 0;
}
