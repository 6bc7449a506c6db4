#include "packet_codec.h"

#include "byte_order.h"
#include "crc16.h"

// Offsets inside a frame (docs/unit-protocol.md §2.1).
#define LENGTH_OFFSET 2u
#define TYPE_OFFSET 3u
#define SEQUENCE_OFFSET 4u
#define TAG_OFFSET 5u
// Bytes needed before the header can be checked: sync pair, length, type.
#define HEADER_CHECK_BYTES 4u

static uint16_t FrameBytes(uint8_t payload_length) {
  return (uint16_t)(FW_FRAME_HEADER_BYTES + (uint16_t)payload_length + FW_FRAME_TRAILER_BYTES);
}

bool fw_is_known_packet_type(uint8_t type) {
  return (type == (uint8_t)FW_PACKET_IMU_DATA) || (type == (uint8_t)FW_PACKET_ADS_DATA) ||
         (type == (uint8_t)FW_PACKET_MAINTENANCE_REQUEST) ||
         (type == (uint8_t)FW_PACKET_MAINTENANCE_RESPONSE);
}

bool fw_is_payload_length_valid(uint8_t type, uint8_t payload_length) {
  bool valid = false;
  if (payload_length > FW_MAX_PAYLOAD_BYTES) {
    valid = false;
  } else if (type == (uint8_t)FW_PACKET_IMU_DATA) {
    valid = (payload_length == FW_IMU_RAW_PAYLOAD_BYTES) ||
            (payload_length == FW_IMU_COMPENSATED_PAYLOAD_BYTES);
  } else if (type == (uint8_t)FW_PACKET_ADS_DATA) {
    valid = (payload_length == FW_ADS_RAW_PAYLOAD_BYTES) ||
            (payload_length == FW_ADS_COMPENSATED_PAYLOAD_BYTES);
  } else if (type == (uint8_t)FW_PACKET_MAINTENANCE_REQUEST) {
    valid = (payload_length >= 1u);
  } else if (type == (uint8_t)FW_PACKET_MAINTENANCE_RESPONSE) {
    valid = (payload_length >= 2u);
  } else {
    valid = false;  // unknown type
  }
  return valid;
}

uint16_t fw_encode_frame(uint8_t type,
                         uint8_t sequence,
                         uint8_t tag,
                         const uint8_t* payload,
                         uint8_t payload_length,
                         uint8_t* out,
                         uint16_t out_capacity) {
  if ((payload_length > FW_MAX_PAYLOAD_BYTES) || (out_capacity < FrameBytes(payload_length))) {
    return 0u;
  }
  out[0] = FW_SYNC_BYTE0;
  out[1] = FW_SYNC_BYTE1;
  out[LENGTH_OFFSET] = payload_length;
  out[TYPE_OFFSET] = type;
  out[SEQUENCE_OFFSET] = sequence;
  out[TAG_OFFSET] = tag;
  for (uint16_t i = 0u; i < payload_length; ++i) {
    out[FW_FRAME_HEADER_BYTES + i] = payload[i];
  }
  const uint16_t crc_covered_bytes =
      (uint16_t)((FW_FRAME_HEADER_BYTES - LENGTH_OFFSET) + (uint16_t)payload_length);
  const uint16_t crc = fw_crc16_ccitt_false(&out[LENGTH_OFFSET], crc_covered_bytes);
  fw_put_u16_le(&out[FW_FRAME_HEADER_BYTES + payload_length], crc);
  return FrameBytes(payload_length);
}

void fw_decoder_init(FwPacketDecoder* decoder) {
  for (uint16_t i = 0u; i < FW_MAX_FRAME_BYTES; ++i) {
    decoder->buffer[i] = 0u;
  }
  decoder->size = 0u;
  decoder->counters.frames_ok = 0u;
  decoder->counters.bad_crc = 0u;
  decoder->counters.bad_length = 0u;
  decoder->counters.unknown_type = 0u;
  decoder->counters.resync_bytes_skipped = 0u;
}

void fw_decoder_discard_buffer(FwPacketDecoder* decoder) {
  decoder->counters.resync_bytes_skipped += decoder->size;
  decoder->size = 0u;
}

static void DropFront(FwPacketDecoder* decoder, uint16_t count) {
  for (uint16_t i = count; i < decoder->size; ++i) {
    decoder->buffer[i - count] = decoder->buffer[i];
  }
  decoder->size = (uint16_t)(decoder->size - count);
}

static FwDecodeEvent RejectCandidate(FwPacketDecoder* decoder,
                                     FwDecodeEvent event,
                                     uint32_t* counter,
                                     FwFrame* frame) {
  ++*counter;
  frame->type = decoder->buffer[TYPE_OFFSET];
  frame->payload_length = decoder->buffer[LENGTH_OFFSET];
  frame->sequence = (decoder->size > SEQUENCE_OFFSET) ? decoder->buffer[SEQUENCE_OFFSET] : 0u;
  frame->tag = (decoder->size > TAG_OFFSET) ? decoder->buffer[TAG_OFFSET] : 0u;
  // Rescan from the byte after the false sync: the candidate's own bytes may hold a real frame.
  DropFront(decoder, 1u);
  ++decoder->counters.resync_bytes_skipped;
  return event;
}

// One step of the scan over the buffered bytes; returns true with *event set when it is decided,
// false when it dropped a byte that cannot start a frame and must be called again.
static bool ScanStep(FwPacketDecoder* decoder, FwFrame* frame, FwDecodeEvent* event) {
  if (decoder->size == 0u) {
    *event = FW_DECODE_NEED_MORE_BYTES;
    return true;
  }
  if ((decoder->buffer[0] != FW_SYNC_BYTE0) ||
      ((decoder->size >= 2u) && (decoder->buffer[1] != FW_SYNC_BYTE1))) {
    DropFront(decoder, 1u);
    ++decoder->counters.resync_bytes_skipped;
    return false;
  }
  if (decoder->size < HEADER_CHECK_BYTES) {
    *event = FW_DECODE_NEED_MORE_BYTES;
    return true;
  }
  const uint8_t type = decoder->buffer[TYPE_OFFSET];
  const uint8_t payload_length = decoder->buffer[LENGTH_OFFSET];
  if (!fw_is_known_packet_type(type)) {
    *event =
        RejectCandidate(decoder, FW_DECODE_UNKNOWN_TYPE, &decoder->counters.unknown_type, frame);
    return true;
  }
  if (!fw_is_payload_length_valid(type, payload_length)) {
    *event = RejectCandidate(decoder, FW_DECODE_BAD_LENGTH, &decoder->counters.bad_length, frame);
    return true;
  }
  const uint16_t frame_bytes = FrameBytes(payload_length);
  if (decoder->size < frame_bytes) {
    *event = FW_DECODE_NEED_MORE_BYTES;
    return true;
  }
  const uint16_t crc_offset = (uint16_t)(FW_FRAME_HEADER_BYTES + (uint16_t)payload_length);
  const uint16_t crc_computed =
      fw_crc16_ccitt_false(&decoder->buffer[LENGTH_OFFSET], (uint16_t)(crc_offset - LENGTH_OFFSET));
  if (crc_computed != fw_get_u16_le(&decoder->buffer[crc_offset])) {
    *event = RejectCandidate(decoder, FW_DECODE_BAD_CRC, &decoder->counters.bad_crc, frame);
    return true;
  }
  frame->type = type;
  frame->sequence = decoder->buffer[SEQUENCE_OFFSET];
  frame->tag = decoder->buffer[TAG_OFFSET];
  frame->payload_length = payload_length;
  for (uint16_t i = 0u; i < payload_length; ++i) {
    frame->payload[i] = decoder->buffer[FW_FRAME_HEADER_BYTES + i];
  }
  DropFront(decoder, frame_bytes);
  ++decoder->counters.frames_ok;
  *event = FW_DECODE_FRAME;
  return true;
}

static FwDecodeEvent Scan(FwPacketDecoder* decoder, FwFrame* frame) {
  FwDecodeEvent event = FW_DECODE_NEED_MORE_BYTES;
  while (!ScanStep(decoder, frame, &event)) {
    // a byte that cannot start a frame was dropped: look again
  }
  return event;
}

FwDecodeResult fw_decoder_feed(FwPacketDecoder* decoder,
                               const uint8_t* bytes,
                               uint16_t count,
                               FwFrame* frame) {
  FwDecodeResult result;
  result.consumed_bytes = 0u;
  result.event = Scan(decoder, frame);
  while ((result.event == FW_DECODE_NEED_MORE_BYTES) && (result.consumed_bytes < count)) {
    // Scan returns NEED_MORE_BYTES only while size < FW_MAX_FRAME_BYTES, so there is room.
    decoder->buffer[decoder->size] = bytes[result.consumed_bytes];
    ++decoder->size;
    ++result.consumed_bytes;
    result.event = Scan(decoder, frame);
  }
  return result;
}
