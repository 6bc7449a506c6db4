// Fuzzes the unit's side of the maintenance protocol (firmware_model/target/maintenance_handler.h):
// the first byte picks an IMU or an ADS unit; the rest is a series of requests, each a length byte
// and that many payload bytes, handed to HandleRequest as CRC-checked frames (the CRC would stop
// the fuzzer before the command parser), so write block, commit, mode and reset follow each other.
// Each response must decode as exactly one frame, nothing dropped or skipped by the stream reader,
// and parse as a maintenance response. The firmware never throws.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "firmware_model/unit_firmware.h"
#include "hil/codecs/unit_protocol_client.h"

namespace fm = adahrs::firmware_model;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const fm::UnitKind kind = data[0] % 2 == 0 ? fm::UnitKind::kImu : fm::UnitKind::kAds;
  fm::FlashStore flash;
  fm::MaintenanceHandler handler({kind, 7, 1, 2, 3}, &flash);
  uint8_t response[fm::kMaxFrameBytes];
  uint8_t sequence = 0;
  for (size_t at = 1; at < size;) {
    fm::Frame frame{};
    frame.type = static_cast<uint8_t>(fm::PacketType::kMaintenanceRequest);
    frame.sequence = sequence++;
    frame.payload_length =
        static_cast<uint8_t>(std::min<size_t>({data[at], size - at - 1, fm::kMaxPayloadBytes}));
    std::memcpy(frame.payload, data + at + 1, frame.payload_length);
    at += 1 + frame.payload_length;
    const uint16_t bytes = handler.HandleRequest(frame, response, sizeof response);
    if (bytes == 0) continue;
    adahrs::hil::StreamReader reader;
    const std::vector<fm::Frame> replies = reader.Push({response, bytes});
    // The reader drops what fails its checks and only counts it: a response it did not decode
    // whole, as exactly one frame and nothing else, is a finding.
    const fm::DecoderCounters& c = reader.counters();
    if (replies.size() != 1 || c.frames_ok != 1 || c.bad_crc != 0 || c.bad_length != 0 ||
        c.unknown_type != 0 || c.resync_bytes_skipped != 0) {
      std::fprintf(stderr,
                   "malformed maintenance response (%zu frames, %u bad CRC, %u bad length, %u "
                   "unknown type, %u bytes skipped): %s\n",
                   replies.size(),
                   static_cast<unsigned>(c.bad_crc),
                   static_cast<unsigned>(c.bad_length),
                   static_cast<unsigned>(c.unknown_type),
                   static_cast<unsigned>(c.resync_bytes_skipped),
                   adahrs::hil::HexTrace({response, bytes}).c_str());
      std::abort();
    }
    (void)adahrs::hil::ParseMaintenanceResponse(replies[0]);  // a ProtocolError here is a finding
  }
  return 0;
}
