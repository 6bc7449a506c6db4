// Fuzzes the unit protocol's host side (docs/unit-protocol.md): the stream decoder in chunks
// whose sizes come from the input, then every parser on each decoded frame, and the data-payload
// decoders on the raw bytes. Refusal: hil::ProtocolError.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware_model/unit_firmware.h"
#include "hil/codecs/unit_protocol_client.h"

namespace fm = adahrs::firmware_model;

namespace {

/// Runs `parse`; a ProtocolError is the parser's refusal, not a finding.
template <typename Parse>
void Refusable(Parse parse) {
  try {
    parse();
  } catch (const adahrs::hil::ProtocolError&) {
  }
}

void ParseFrame(const fm::Frame& frame) {
  Refusable([&] {
    const adahrs::hil::MaintenanceResponse response = adahrs::hil::ParseMaintenanceResponse(frame);
    Refusable([&] { (void)adahrs::hil::ParseIdentify(response); });
    Refusable([&] { (void)adahrs::hil::ParseCommit(response); });
    Refusable([&] { (void)adahrs::hil::ParseReadBlock(response); });
    Refusable([&] { (void)adahrs::hil::ParseCounters(response); });
  });
  Refusable([&] { (void)adahrs::hil::ParseImuData(frame); });
  Refusable([&] { (void)adahrs::hil::ParseAdsData(frame); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const size_t chunk_bytes = 1 + data[0] % 64;  // first byte: the transport's read size
  std::span<const uint8_t> stream(data + 1, size - 1);
  adahrs::hil::StreamReader reader;
  for (size_t at = 0; at < stream.size(); at += chunk_bytes) {
    for (const fm::Frame& frame :
         reader.Push(stream.subspan(at, std::min(chunk_bytes, stream.size() - at)))) {
      ParseFrame(frame);
    }
  }
  const auto length = static_cast<uint8_t>(std::min<size_t>(stream.size(), 255));
  fm::ImuDataPayload imu{};
  (void)fm::DecodeImuPayload(stream.data(), length, &imu);
  fm::AdsDataPayload ads{};
  (void)fm::DecodeAdsPayload(stream.data(), length, &ads);
  return 0;
}
