#include "firmware_model/target/packet_codec.h"

#include "firmware_model/target/byte_order.h"
#include "firmware_model/target/crc16.h"

namespace adahrs::firmware_model {
namespace {

// Offsets inside a frame (docs/unit-protocol.md §2.1).
constexpr uint16_t kLengthOffset = 2;
constexpr uint16_t kTypeOffset = 3;
constexpr uint16_t kSequenceOffset = 4;
constexpr uint16_t kTagOffset = 5;
// Bytes needed before the header can be checked: sync pair, length, type.
constexpr uint16_t kHeaderCheckBytes = 4;

uint16_t FrameBytes(uint8_t payload_length) {
  return static_cast<uint16_t>(kFrameHeaderBytes + payload_length + kFrameTrailerBytes);
}

}  // namespace

bool IsKnownPacketType(uint8_t type) {
  switch (static_cast<PacketType>(type)) {
    case PacketType::kImuData:
    case PacketType::kAdsData:
    case PacketType::kMaintenanceRequest:
    case PacketType::kMaintenanceResponse:
      return true;
  }
  return false;
}

bool IsPayloadLengthValid(uint8_t type, uint8_t payload_length) {
  if (payload_length > kMaxPayloadBytes) {
    return false;
  }
  switch (static_cast<PacketType>(type)) {
    case PacketType::kImuData:
      return payload_length == kImuRawPayloadBytes || payload_length == kImuCompensatedPayloadBytes;
    case PacketType::kAdsData:
      return payload_length == kAdsRawPayloadBytes || payload_length == kAdsCompensatedPayloadBytes;
    case PacketType::kMaintenanceRequest:
      return payload_length >= 1;
    case PacketType::kMaintenanceResponse:
      return payload_length >= 2;
  }
  return false;
}

uint16_t EncodeFrame(uint8_t type,
                     uint8_t sequence,
                     uint8_t tag,
                     const uint8_t* payload,
                     uint8_t payload_length,
                     uint8_t* out,
                     uint16_t out_capacity) {
  if (payload_length > kMaxPayloadBytes || out_capacity < FrameBytes(payload_length)) {
    return 0;
  }
  out[0] = kSyncByte0;
  out[1] = kSyncByte1;
  out[kLengthOffset] = payload_length;
  out[kTypeOffset] = type;
  out[kSequenceOffset] = sequence;
  out[kTagOffset] = tag;
  for (uint16_t i = 0; i < payload_length; ++i) {
    out[kFrameHeaderBytes + i] = payload[i];
  }
  const uint16_t crc_covered_bytes =
      static_cast<uint16_t>(kFrameHeaderBytes - kLengthOffset + payload_length);
  const uint16_t crc = Crc16CcittFalse(out + kLengthOffset, crc_covered_bytes);
  PutU16Le(out + kFrameHeaderBytes + payload_length, crc);
  return FrameBytes(payload_length);
}

DecodeResult PacketDecoder::Feed(const uint8_t* bytes, uint16_t count, Frame* frame) {
  uint16_t consumed = 0;
  while (true) {
    const DecodeEvent event = Scan(frame);
    if (event != DecodeEvent::kNeedMoreBytes || consumed == count) {
      return DecodeResult{consumed, event};
    }
    // Scan returns kNeedMoreBytes only while size_ < kMaxFrameBytes, so there is room.
    buffer_[size_] = bytes[consumed];
    ++size_;
    ++consumed;
  }
}

void PacketDecoder::DiscardBuffer() {
  counters_.resync_bytes_skipped += size_;
  size_ = 0;
}

void PacketDecoder::DropFront(uint16_t count) {
  for (uint16_t i = count; i < size_; ++i) {
    buffer_[i - count] = buffer_[i];
  }
  size_ = static_cast<uint16_t>(size_ - count);
}

DecodeEvent PacketDecoder::RejectCandidate(DecodeEvent event, uint32_t* counter, Frame* frame) {
  ++*counter;
  frame->type = buffer_[kTypeOffset];
  frame->payload_length = buffer_[kLengthOffset];
  frame->sequence = size_ > kSequenceOffset ? buffer_[kSequenceOffset] : 0;
  frame->tag = size_ > kTagOffset ? buffer_[kTagOffset] : 0;
  // Rescan from the byte after the false sync: the candidate's own bytes may hold a real frame.
  DropFront(1);
  ++counters_.resync_bytes_skipped;
  return event;
}

DecodeEvent PacketDecoder::Scan(Frame* frame) {
  while (true) {
    if (size_ == 0) {
      return DecodeEvent::kNeedMoreBytes;
    }
    if (buffer_[0] != kSyncByte0) {
      DropFront(1);
      ++counters_.resync_bytes_skipped;
      continue;
    }
    if (size_ < 2) {
      return DecodeEvent::kNeedMoreBytes;
    }
    if (buffer_[1] != kSyncByte1) {
      DropFront(1);
      ++counters_.resync_bytes_skipped;
      continue;
    }
    if (size_ < kHeaderCheckBytes) {
      return DecodeEvent::kNeedMoreBytes;
    }
    const uint8_t type = buffer_[kTypeOffset];
    const uint8_t payload_length = buffer_[kLengthOffset];
    if (!IsKnownPacketType(type)) {
      return RejectCandidate(DecodeEvent::kUnknownType, &counters_.unknown_type, frame);
    }
    if (!IsPayloadLengthValid(type, payload_length)) {
      return RejectCandidate(DecodeEvent::kBadLength, &counters_.bad_length, frame);
    }
    const uint16_t frame_bytes = FrameBytes(payload_length);
    if (size_ < frame_bytes) {
      return DecodeEvent::kNeedMoreBytes;
    }
    const uint16_t crc_offset = static_cast<uint16_t>(kFrameHeaderBytes + payload_length);
    const uint16_t crc_computed =
        Crc16CcittFalse(buffer_ + kLengthOffset, static_cast<uint16_t>(crc_offset - kLengthOffset));
    if (crc_computed != GetU16Le(buffer_ + crc_offset)) {
      return RejectCandidate(DecodeEvent::kBadCrc, &counters_.bad_crc, frame);
    }
    frame->type = type;
    frame->sequence = buffer_[kSequenceOffset];
    frame->tag = buffer_[kTagOffset];
    frame->payload_length = payload_length;
    for (uint16_t i = 0; i < payload_length; ++i) {
      frame->payload[i] = buffer_[kFrameHeaderBytes + i];
    }
    DropFront(frame_bytes);
    ++counters_.frames_ok;
    return DecodeEvent::kFrame;
  }
}

}  // namespace adahrs::firmware_model
