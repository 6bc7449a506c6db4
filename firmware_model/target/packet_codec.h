// Framing of the unit serial protocol (docs/unit-protocol.md §2-3): an encoder into a caller's
// fixed buffer and a streaming decoder with a fixed internal buffer.
//
// The decoder hunts for the sync pair, checks the header (known type, payload length allowed
// for that type), waits for the whole frame, checks the CRC-16 and hands out complete frames.
// After any rejection it drops only the first sync byte and rescans the bytes it already holds,
// so an intact frame that follows garbage, a truncated frame or a false sync inside a payload is
// always found (the buffer holds one maximum-length frame, the longest window a false sync can
// claim). Errors are reported as events and counted by kind.
// Firmware discipline: fixed-width integers, no heap, no exceptions; builds for the dsPIC.
// Not modelled: UART overrun/framing errors (the decoder sees bytes only) and inter-byte
// timeouts; a frame is delimited by its length field alone.
#pragma once

#include <cstdint>

#include "firmware_model/target/unit_protocol.h"

namespace adahrs::firmware_model {

/// One frame without its sync bytes and CRC. `type` is the raw type byte.
struct Frame {
  uint8_t type;
  uint8_t sequence;
  uint8_t tag;
  uint8_t payload_length;
  uint8_t payload[kMaxPayloadBytes];
};

/// True for a type byte listed in PacketType.
bool IsKnownPacketType(uint8_t type);

/// True if `payload_length` is allowed for packet type `type` (§2.2): an IMU data payload is
/// 43 (raw) or 81 (compensated) bytes, an ADS payload 21 or 31, a request 1..250, a response
/// 2..250. False for an unknown type.
bool IsPayloadLengthValid(uint8_t type, uint8_t payload_length);

/// Writes one frame into `out` and returns the number of bytes written (8 + payload_length);
/// returns 0 and writes nothing if `payload_length` exceeds kMaxPayloadBytes or `out_capacity`
/// is too small. The length/type combination is not checked, so tests can build frames the
/// decoder must refuse.
uint16_t EncodeFrame(uint8_t type,
                     uint8_t sequence,
                     uint8_t tag,
                     const uint8_t* payload,
                     uint8_t payload_length,
                     uint8_t* out,
                     uint16_t out_capacity);

/// What one call of PacketDecoder::Feed produced.
enum class DecodeEvent : uint8_t {
  kNeedMoreBytes,  ///< every offered byte was taken, nothing complete yet
  kFrame,          ///< a frame passed every check; it is in *frame
  kBadCrc,         ///< a complete candidate failed its CRC; header fields in *frame as received
  kBadLength,      ///< header with a length not allowed for its type; type and length in *frame
  kUnknownType,    ///< header with an unknown type byte; type and length in *frame
};

struct DecodeResult {
  uint16_t consumed_bytes;  ///< bytes taken from the offered chunk
  DecodeEvent event;
};

/// Running totals since construction.
struct DecoderCounters {
  uint32_t frames_ok;
  uint32_t bad_crc;
  uint32_t bad_length;
  uint32_t unknown_type;
  uint32_t resync_bytes_skipped;  ///< bytes discarded that were not part of an accepted frame
};

/// Streaming frame decoder with a fixed buffer of one maximum-length frame.
class PacketDecoder {
 public:
  /// Takes bytes from `bytes[0, count)` until an event other than kNeedMoreBytes occurs, and
  /// returns how many it took with that event. Call again with the rest of the chunk (or with
  /// count 0) until it returns kNeedMoreBytes: one byte can complete several buffered frames.
  /// On kFrame, *frame holds the frame; on an error event only its header fields are set.
  DecodeResult Feed(const uint8_t* bytes, uint16_t count, Frame* frame);

  const DecoderCounters& counters() const { return counters_; }

  /// Discards buffered bytes (counted as skipped); counters are kept.
  void DiscardBuffer();

 private:
  DecodeEvent Scan(Frame* frame);
  void DropFront(uint16_t count);
  DecodeEvent RejectCandidate(DecodeEvent event, uint32_t* counter, Frame* frame);

  uint8_t buffer_[kMaxFrameBytes] = {};
  uint16_t size_ = 0;
  DecoderCounters counters_ = {};
};

}  // namespace adahrs::firmware_model
