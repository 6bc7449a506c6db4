#include "firmware_model/target/maintenance_handler.h"

#include "firmware_model/target/byte_order.h"
#include "firmware_model/target/data_payloads.h"

namespace adahrs::firmware_model {
namespace {

// Request payload lengths (docs/unit-protocol.md §6.2): command byte plus arguments.
constexpr uint8_t kNoArgumentRequestBytes = 1;
constexpr uint8_t kOneArgumentRequestBytes = 2;
constexpr uint8_t kWriteBlockHeaderBytes = 3;  // command, block id, word count
// A block never exceeds what one request can carry.
constexpr uint8_t kMaxBlockWords = (kMaxPayloadBytes - kWriteBlockHeaderBytes) / 2;
static_assert(kImuMaxBlockWords <= kMaxBlockWords && kAdsMaxBlockWords <= kMaxBlockWords);

// IMU blocks are 0x01..0x1B without gaps (0x01..0x0F the format-2 set); ADS blocks 0x21..0x22.
constexpr uint8_t kImuBlockCount = kImuBlockLast - kImuBlockThermalFirst + 1;
constexpr uint8_t kImuFormat2BlockCount = kImuBlockCg - kImuBlockThermalFirst + 1;
constexpr uint32_t kImuFormat2Mask = (uint32_t{1} << kImuFormat2BlockCount) - 1u;
constexpr uint8_t kAdsBlockCount = kAdsBlockAirspeed - kAdsBlockAltitude + 1;

ResultCode ToResultCode(ConstantsStatus status) {
  switch (status) {
    case ConstantsStatus::kOk:
      return ResultCode::kAck;
    case ConstantsStatus::kUnknownBlock:
      return ResultCode::kUnknownBlock;
    case ConstantsStatus::kWrongLength:
      return ResultCode::kBlockWrongLength;
    case ConstantsStatus::kOutOfRange:
      return ResultCode::kConstantOutOfRange;
    case ConstantsStatus::kWouldOverflow:
      return ResultCode::kConstantOverflow;
    case ConstantsStatus::kNullArgument:
      return ResultCode::kBadArgument;
  }
  return ResultCode::kBadArgument;
}

}  // namespace

MaintenanceHandler::MaintenanceHandler(const UnitIdentity& identity, FlashStore* flash)
    : identity_(identity), flash_(flash) {
  PowerCycle();
}

void MaintenanceHandler::InitConstants() {
  ImuConstantsInit(&imu_constants_);
  AdsConstantsInit(&ads_constants_);
  blocks_valid_mask_ = 0;
  constants_valid_ = false;
  constants_version_ = 0;
  constants_crc_ = 0;
}

void MaintenanceHandler::PowerCycle() {
  decoder_ = PacketDecoder();
  counters_ = HandlerCounters{};
  mode_ = 0;
  tag_ = 0;
  data_sequence_ = 0;
  LoadCommittedConstants();
}

// The image payload is a list of records [block id, word count, words...], one per block.
void MaintenanceHandler::LoadCommittedConstants() {
  InitConstants();
  uint16_t image_length = 0;
  if (flash_->Load(identity_.kind, image_words_, kFlashMaxPayloadWords, &image_length) !=
      FlashStatus::kOk) {
    return;
  }
  uint32_t loaded_mask = 0;
  uint16_t position = 0;
  while (position + 2 <= image_length) {
    const int16_t block_word = image_words_[position];
    const int16_t count_word = image_words_[position + 1];
    uint8_t index = 0;
    if (block_word < 0 || block_word > 0xFF || count_word < 0 || count_word > kMaxBlockWords ||
        position + 2 + count_word > image_length ||
        !BlockIndex(static_cast<uint8_t>(block_word), &index) ||
        WriteBlock(static_cast<uint8_t>(block_word),
                   image_words_ + position + 2,
                   static_cast<uint8_t>(count_word)) != ConstantsStatus::kOk) {
      InitConstants();
      return;
    }
    loaded_mask |= uint32_t{1} << index;
    position = static_cast<uint16_t>(position + 2 + count_word);
  }
  if (position != image_length || !IsCompleteSet(loaded_mask)) {
    InitConstants();
    return;
  }
  const FlashImageInfo info = flash_->Inspect(identity_.kind);
  blocks_valid_mask_ = loaded_mask;
  constants_valid_ = true;
  constants_version_ = info.constants_version;
  constants_crc_ = info.image_crc;
}

uint8_t MaintenanceHandler::TakeDataSequence() {
  const uint8_t sequence = data_sequence_;
  data_sequence_ = static_cast<uint8_t>(data_sequence_ + 1);
  return sequence;
}

uint8_t MaintenanceHandler::BlockCount() const {
  return identity_.kind == UnitKind::kImu ? kImuBlockCount : kAdsBlockCount;
}

uint8_t MaintenanceHandler::BlockIdAt(uint8_t index) const {
  const uint8_t first = identity_.kind == UnitKind::kImu ? uint8_t{kImuBlockThermalFirst}
                                                         : uint8_t{kAdsBlockAltitude};
  return static_cast<uint8_t>(first + index);
}

bool MaintenanceHandler::BlockIndex(uint8_t block_id, uint8_t* index) const {
  for (uint8_t i = 0; i < BlockCount(); ++i) {
    if (BlockIdAt(i) == block_id) {
      *index = i;
      return true;
    }
  }
  return false;
}

uint32_t MaintenanceHandler::AllBlocksMask() const { return (uint32_t{1} << BlockCount()) - 1u; }

bool MaintenanceHandler::IsCompleteSet(uint32_t mask) const {
  if (identity_.kind != UnitKind::kImu) return mask == AllBlocksMask();
  const uint32_t format3 = AllBlocksMask() & ~kImuFormat2Mask;
  return (mask & kImuFormat2Mask) == kImuFormat2Mask &&
         ((mask & format3) == 0 || (mask & format3) == format3);
}

ConstantsStatus MaintenanceHandler::WriteBlock(uint8_t block_id,
                                               const int16_t* words,
                                               uint8_t count) {
  return identity_.kind == UnitKind::kImu
             ? ImuConstantsWriteBlock(&imu_constants_, block_id, words, count)
             : AdsConstantsWriteBlock(&ads_constants_, block_id, words, count);
}

ConstantsStatus MaintenanceHandler::ReadBlock(uint8_t block_id,
                                              int16_t* words,
                                              uint8_t capacity,
                                              uint8_t* count) const {
  return identity_.kind == UnitKind::kImu
             ? ImuConstantsReadBlock(&imu_constants_, block_id, words, capacity, count)
             : AdsConstantsReadBlock(&ads_constants_, block_id, words, capacity, count);
}

PortResult MaintenanceHandler::Receive(const uint8_t* bytes,
                                       uint16_t count,
                                       uint8_t* response,
                                       uint16_t response_capacity) {
  uint16_t consumed = 0;
  while (true) {
    const DecodeResult result =
        decoder_.Feed(bytes + consumed, static_cast<uint16_t>(count - consumed), &frame_);
    consumed = static_cast<uint16_t>(consumed + result.consumed_bytes);
    uint16_t response_bytes = 0;
    if (result.event == DecodeEvent::kFrame) {
      response_bytes = HandleRequest(frame_, response, response_capacity);
    } else if (result.event == DecodeEvent::kBadCrc &&
               frame_.type == static_cast<uint8_t>(PacketType::kMaintenanceRequest)) {
      response_bytes = Respond(static_cast<uint8_t>(MaintenanceCommand::kNone),
                               frame_.sequence,
                               ResultCode::kBadCrc,
                               response,
                               response_capacity);
    } else if (result.event == DecodeEvent::kNeedMoreBytes) {
      return PortResult{consumed, 0};
    }
    if (response_bytes != 0) {
      return PortResult{consumed, response_bytes};
    }
  }
}

uint16_t MaintenanceHandler::HandleRequest(const Frame& frame,
                                           uint8_t* response,
                                           uint16_t response_capacity) {
  if (frame.type != static_cast<uint8_t>(PacketType::kMaintenanceRequest) ||
      frame.payload_length < 1 || response_capacity < kMaxFrameBytes) {
    return 0;
  }
  data_length_ = 0;
  const uint8_t command = frame.payload[0];
  ResultCode result = ResultCode::kUnknownCommand;
  switch (static_cast<MaintenanceCommand>(command)) {
    case MaintenanceCommand::kSetMode:
      result = DoSetMode(frame);
      break;
    case MaintenanceCommand::kSetTag:
      result = DoSetTag(frame);
      break;
    case MaintenanceCommand::kWriteBlock:
      result = DoWriteBlock(frame);
      break;
    case MaintenanceCommand::kReadBlock:
      result = DoReadBlock(frame);
      break;
    case MaintenanceCommand::kCommit:
      result = DoCommit(frame);
      break;
    case MaintenanceCommand::kIdentify:
      result = DoIdentify(frame);
      break;
    case MaintenanceCommand::kReset:
      result = DoReset(frame);
      break;
    case MaintenanceCommand::kReadCounters:
      result = DoReadCounters(frame);
      break;
    case MaintenanceCommand::kNone:
      break;
  }
  return Respond(command, frame.sequence, result, response, response_capacity);
}

uint16_t MaintenanceHandler::Respond(uint8_t command,
                                     uint8_t sequence,
                                     ResultCode result,
                                     uint8_t* response,
                                     uint16_t response_capacity) {
  if (result == ResultCode::kAck) {
    ++counters_.requests_acked;
  } else {
    data_length_ = 0;
    ++counters_.requests_naked;
    ++counters_.naks_by_code[static_cast<uint8_t>(result)];
  }
  uint8_t payload[kMaxPayloadBytes];
  payload[0] = command;
  payload[1] = static_cast<uint8_t>(result);
  for (uint8_t i = 0; i < data_length_; ++i) {
    payload[2 + i] = data_[i];
  }
  return EncodeFrame(static_cast<uint8_t>(PacketType::kMaintenanceResponse),
                     sequence,
                     tag_,
                     payload,
                     static_cast<uint8_t>(2 + data_length_),
                     response,
                     response_capacity);
}

ResultCode MaintenanceHandler::DoSetMode(const Frame& frame) {
  if (frame.payload_length != kOneArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  const uint8_t mode = frame.payload[1];
  const bool defined = identity_.kind == UnitKind::kImu ? IsImuModeByte(mode) : IsAdsModeByte(mode);
  if (!defined) {
    return ResultCode::kBadArgument;
  }
  // Raw is 0 for both unit kinds; every other mode uses the constants.
  if (mode != 0 && !constants_valid_) {
    return ResultCode::kNoValidConstants;
  }
  mode_ = mode;
  data_[0] = mode_;
  data_length_ = 1;
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoSetTag(const Frame& frame) {
  if (frame.payload_length != kOneArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  tag_ = frame.payload[1];
  data_[0] = tag_;
  data_length_ = 1;
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoWriteBlock(const Frame& frame) {
  if (frame.payload_length < kWriteBlockHeaderBytes) {
    return ResultCode::kBadLength;
  }
  const uint8_t block_id = frame.payload[1];
  const uint8_t word_count = frame.payload[2];
  if (frame.payload_length != kWriteBlockHeaderBytes + 2 * word_count) {
    return ResultCode::kBadLength;
  }
  uint8_t index = 0;
  if (!BlockIndex(block_id, &index)) {
    return ResultCode::kUnknownBlock;
  }
  int16_t words[kMaxBlockWords];
  for (uint8_t i = 0; i < word_count; ++i) {
    words[i] = GetI16Le(frame.payload + kWriteBlockHeaderBytes + 2 * i);
  }
  const ConstantsStatus status = WriteBlock(block_id, words, word_count);
  if (status != ConstantsStatus::kOk) {
    return ToResultCode(status);
  }
  blocks_valid_mask_ |= uint32_t{1} << index;
  data_[0] = block_id;
  data_length_ = 1;
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoReadBlock(const Frame& frame) {
  if (frame.payload_length != kOneArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  const uint8_t block_id = frame.payload[1];
  uint8_t index = 0;
  if (!BlockIndex(block_id, &index)) {
    return ResultCode::kUnknownBlock;
  }
  int16_t words[kMaxBlockWords];
  uint8_t word_count = 0;
  const ConstantsStatus status = ReadBlock(block_id, words, kMaxBlockWords, &word_count);
  if (status != ConstantsStatus::kOk) {
    return ToResultCode(status);
  }
  data_[0] = block_id;
  data_[1] = word_count;
  for (uint8_t i = 0; i < word_count; ++i) {
    PutI16Le(data_ + 2 + 2 * i, words[i]);
  }
  data_length_ = static_cast<uint8_t>(2 + 2 * word_count);
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoCommit(const Frame& frame) {
  if (frame.payload_length != kNoArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  if (!IsCompleteSet(blocks_valid_mask_)) {
    return ResultCode::kIncompleteConstants;
  }
  uint16_t position = 0;
  for (uint8_t i = 0; i < BlockCount(); ++i) {
    uint8_t word_count = 0;
    const uint16_t free_words = static_cast<uint16_t>(kFlashMaxPayloadWords - position);
    if (free_words < 2) {
      return ResultCode::kFlashError;
    }
    const uint8_t capacity =
        free_words - 2 < kMaxBlockWords ? static_cast<uint8_t>(free_words - 2) : kMaxBlockWords;
    if (ReadBlock(BlockIdAt(i), image_words_ + position + 2, capacity, &word_count) !=
        ConstantsStatus::kOk) {
      return ResultCode::kFlashError;
    }
    image_words_[position] = static_cast<int16_t>(BlockIdAt(i));
    image_words_[position + 1] = static_cast<int16_t>(word_count);
    position = static_cast<uint16_t>(position + 2 + word_count);
  }
  if (flash_->Commit(identity_.kind, image_words_, position) != FlashStatus::kOk) {
    return ResultCode::kFlashError;
  }
  const FlashImageInfo info = flash_->Inspect(identity_.kind);
  constants_valid_ = true;
  constants_version_ = info.constants_version;
  constants_crc_ = info.image_crc;
  PutU16Le(data_, constants_version_);
  PutU16Le(data_ + 2, constants_crc_);
  data_length_ = 4;
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoIdentify(const Frame& frame) {
  if (frame.payload_length != kNoArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  data_[0] = static_cast<uint8_t>(identity_.kind);
  PutU32Le(data_ + 1, identity_.serial_number);
  data_[5] = identity_.firmware_major;
  data_[6] = identity_.firmware_minor;
  data_[7] = identity_.firmware_patch;
  data_[8] = constants_valid_ ? 1 : 0;
  PutU16Le(data_ + 9, constants_version_);
  PutU16Le(data_ + 11, constants_crc_);
  data_[13] = mode_;
  data_[14] = tag_;
  data_length_ = 15;
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoReset(const Frame& frame) {
  if (frame.payload_length != kNoArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  PowerCycle();
  data_[0] = constants_valid_ ? 1 : 0;
  data_length_ = 1;
  return ResultCode::kAck;
}

ResultCode MaintenanceHandler::DoReadCounters(const Frame& frame) {
  if (frame.payload_length != kNoArgumentRequestBytes) {
    return ResultCode::kBadLength;
  }
  const DecoderCounters& decoder = decoder_.counters();
  PutU32Le(data_, decoder.frames_ok);
  PutU32Le(data_ + 4, decoder.bad_crc);
  PutU32Le(data_ + 8, decoder.bad_length);
  PutU32Le(data_ + 12, decoder.unknown_type);
  PutU32Le(data_ + 16, decoder.resync_bytes_skipped);
  PutU32Le(data_ + 20, counters_.requests_acked);
  PutU32Le(data_ + 24, counters_.requests_naked);
  data_length_ = 28;
  return ResultCode::kAck;
}

}  // namespace adahrs::firmware_model
