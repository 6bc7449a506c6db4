// Framing of the unit serial protocol (docs/unit-protocol.md §2-3): an encoder into a caller's
// fixed buffer and a streaming decoder with a fixed internal buffer.
//
// The decoder hunts for the sync pair, checks the header (known type, payload length allowed
// for that type), waits for the whole frame, checks the CRC-16 and hands out complete frames.
// After any rejection it drops only the first sync byte and rescans the bytes it already holds,
// so an intact frame that follows garbage, a truncated frame or a false sync inside a payload is
// always found (the buffer holds one maximum-length frame, the longest window a false sync can
// claim). Errors are reported as events and counted by kind.
// Fixed-width integers, no heap, fixed buffers; builds for the dsPIC.
// Not modelled: UART overrun/framing errors (the decoder sees bytes only) and inter-byte
// timeouts; a frame is delimited by its length field alone.
#ifndef ADAHRS_FW_PACKET_CODEC_H
#define ADAHRS_FW_PACKET_CODEC_H

#include <stdbool.h>
#include <stdint.h>

#include "unit_protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

/// One frame without its sync bytes and CRC. `type` is the raw type byte.
typedef struct {
  uint8_t type;
  uint8_t sequence;
  uint8_t tag;
  uint8_t payload_length;
  uint8_t payload[FW_MAX_PAYLOAD_BYTES];
} FwFrame;

/// True for a type byte listed in FwPacketType.
bool fw_is_known_packet_type(uint8_t type);

/// True if `payload_length` is allowed for packet type `type` (§2.2): an IMU data payload is
/// 43 (raw) or 81 (compensated) bytes, an ADS payload 21 or 31, a request 1..250, a response
/// 2..250. False for an unknown type.
bool fw_is_payload_length_valid(uint8_t type, uint8_t payload_length);

/// Writes one frame into `out` and returns the number of bytes written (8 + payload_length);
/// returns 0 and writes nothing if `payload_length` exceeds FW_MAX_PAYLOAD_BYTES or
/// `out_capacity` is too small. The length/type combination is not checked, so tests can build
/// frames the decoder must refuse.
uint16_t fw_encode_frame(uint8_t type,
                         uint8_t sequence,
                         uint8_t tag,
                         const uint8_t* payload,
                         uint8_t payload_length,
                         uint8_t* out,
                         uint16_t out_capacity);

/// What one call of fw_decoder_feed produced.
typedef enum {
  FW_DECODE_NEED_MORE_BYTES,  ///< every offered byte was taken, nothing complete yet
  FW_DECODE_FRAME,            ///< a frame passed every check; it is in *frame
  FW_DECODE_BAD_CRC,          ///< a whole candidate failed its CRC; its header fields in *frame
  FW_DECODE_BAD_LENGTH,       ///< a length not allowed for the type; type and length in *frame
  FW_DECODE_UNKNOWN_TYPE      ///< an unknown type byte; type and length in *frame
} FwDecodeEvent;

typedef struct {
  uint16_t consumed_bytes;  ///< bytes taken from the offered chunk
  FwDecodeEvent event;
} FwDecodeResult;

/// Running totals since initialisation.
typedef struct {
  uint32_t frames_ok;
  uint32_t bad_crc;
  uint32_t bad_length;
  uint32_t unknown_type;
  uint32_t resync_bytes_skipped;  ///< bytes discarded that were not part of an accepted frame
} FwDecoderCounters;

/// Streaming frame decoder with a fixed buffer of one maximum-length frame.
typedef struct {
  uint8_t buffer[FW_MAX_FRAME_BYTES];
  uint16_t size;
  FwDecoderCounters counters;
} FwPacketDecoder;

/// An empty decoder with zero counters.
void fw_decoder_init(FwPacketDecoder* decoder);

/// Takes bytes from `bytes[0, count)` until an event other than NEED_MORE_BYTES occurs, and
/// returns how many it took with that event. Call again with the rest of the chunk (or with
/// count 0) until it returns NEED_MORE_BYTES: one byte can complete several buffered frames.
/// On FRAME, *frame holds the frame; on an error event only its header fields are set.
FwDecodeResult fw_decoder_feed(FwPacketDecoder* decoder,
                               const uint8_t* bytes,
                               uint16_t count,
                               FwFrame* frame);

/// Discards buffered bytes (counted as skipped); counters are kept.
void fw_decoder_discard_buffer(FwPacketDecoder* decoder);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_PACKET_CODEC_H
