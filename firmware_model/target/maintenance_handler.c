#include "maintenance_handler.h"

#include "byte_order.h"
#include "data_payloads.h"

// Request payload lengths (docs/unit-protocol.md §6.2): command byte plus arguments.
#define NO_ARGUMENT_REQUEST_BYTES 1u
#define ONE_ARGUMENT_REQUEST_BYTES 2u
#define WRITE_BLOCK_HEADER_BYTES 3u  // command, block id, word count
// A block never exceeds what one request can carry.
#define MAX_BLOCK_WORDS ((FW_MAX_PAYLOAD_BYTES - WRITE_BLOCK_HEADER_BYTES) / 2u)

// IMU blocks are 0x01..0x1B without gaps (0x01..0x0F the format-2 set); ADS blocks 0x21..0x22.
#define IMU_BLOCK_COUNT (FW_IMU_BLOCK_LAST - FW_IMU_BLOCK_THERMAL_FIRST + 1u)
#define IMU_FORMAT2_BLOCK_COUNT (FW_IMU_BLOCK_CG - FW_IMU_BLOCK_THERMAL_FIRST + 1u)
#define IMU_FORMAT2_MASK ((UINT32_C(1) << IMU_FORMAT2_BLOCK_COUNT) - 1u)
#define ADS_BLOCK_COUNT (FW_ADS_BLOCK_AIRSPEED - FW_ADS_BLOCK_ALTITUDE + 1u)

#if (FW_IMU_MAX_BLOCK_WORDS > MAX_BLOCK_WORDS) || (FW_ADS_MAX_BLOCK_WORDS > MAX_BLOCK_WORDS)
#error "a constants block does not fit one WRITE_BLOCK request"
#endif

static FwResultCode ToResultCode(FwConstantsStatus status) {
  FwResultCode code = FW_RESULT_BAD_ARGUMENT;
  switch (status) {
    case FW_CONSTANTS_OK:
      code = FW_RESULT_ACK;
      break;
    case FW_CONSTANTS_UNKNOWN_BLOCK:
      code = FW_RESULT_UNKNOWN_BLOCK;
      break;
    case FW_CONSTANTS_WRONG_LENGTH:
      code = FW_RESULT_BLOCK_WRONG_LENGTH;
      break;
    case FW_CONSTANTS_OUT_OF_RANGE:
      code = FW_RESULT_CONSTANT_OUT_OF_RANGE;
      break;
    case FW_CONSTANTS_WOULD_OVERFLOW:
      code = FW_RESULT_CONSTANT_OVERFLOW;
      break;
    default:  // FW_CONSTANTS_NULL_ARGUMENT
      code = FW_RESULT_BAD_ARGUMENT;
      break;
  }
  return code;
}

static bool IsImu(const FwMaintenanceHandler* h) { return h->identity.kind == FW_UNIT_IMU; }

static void InitConstants(FwMaintenanceHandler* h) {
  fw_imu_constants_init(&h->imu_constants);
  fw_ads_constants_init(&h->ads_constants);
  h->blocks_valid_mask = 0u;
  h->constants_valid = false;
  h->constants_version = 0u;
  h->constants_crc = 0u;
}

static uint8_t BlockCount(const FwMaintenanceHandler* h) {
  return IsImu(h) ? (uint8_t)IMU_BLOCK_COUNT : (uint8_t)ADS_BLOCK_COUNT;
}

static uint8_t BlockIdAt(const FwMaintenanceHandler* h, uint8_t index) {
  const uint8_t first =
      IsImu(h) ? (uint8_t)FW_IMU_BLOCK_THERMAL_FIRST : (uint8_t)FW_ADS_BLOCK_ALTITUDE;
  return (uint8_t)(first + index);
}

static bool BlockIndex(const FwMaintenanceHandler* h, uint8_t block_id, uint8_t* index) {
  for (uint8_t i = 0u; i < BlockCount(h); ++i) {
    if (BlockIdAt(h, i) == block_id) {
      *index = i;
      return true;
    }
  }
  return false;
}

static uint32_t AllBlocksMask(const FwMaintenanceHandler* h) {
  return (UINT32_C(1) << BlockCount(h)) - 1u;
}

// True when `mask` holds a set the unit can run: every block for the ADS; for the IMU the
// format-2 blocks 0x01..0x0F, and the format-3 blocks 0x10..0x1B all or none.
static bool IsCompleteSet(const FwMaintenanceHandler* h, uint32_t mask) {
  if (!IsImu(h)) {
    return mask == AllBlocksMask(h);
  }
  const uint32_t format3 = AllBlocksMask(h) & ~IMU_FORMAT2_MASK;
  return ((mask & IMU_FORMAT2_MASK) == IMU_FORMAT2_MASK) &&
         (((mask & format3) == 0u) || ((mask & format3) == format3));
}

static FwConstantsStatus WriteBlock(FwMaintenanceHandler* h,
                                    uint8_t block_id,
                                    const int16_t* words,
                                    uint8_t count) {
  return IsImu(h) ? fw_imu_constants_write_block(&h->imu_constants, block_id, words, count)
                  : fw_ads_constants_write_block(&h->ads_constants, block_id, words, count);
}

static FwConstantsStatus ReadBlock(const FwMaintenanceHandler* h,
                                   uint8_t block_id,
                                   int16_t* words,
                                   uint8_t capacity,
                                   uint8_t* count) {
  return IsImu(h)
             ? fw_imu_constants_read_block(&h->imu_constants, block_id, words, capacity, count)
             : fw_ads_constants_read_block(&h->ads_constants, block_id, words, capacity, count);
}

// One record of a flash image at `position`: [block id, word count, words...]. Writes the block
// and sets its bit in *loaded_mask; false if the record is malformed or the block refused.
static bool LoadRecord(FwMaintenanceHandler* h,
                       uint16_t position,
                       uint16_t image_length,
                       uint32_t* loaded_mask,
                       uint16_t* next) {
  const int16_t block_word = h->image_words[position];
  const int16_t count_word = h->image_words[position + 1u];
  uint8_t index = 0u;
  if ((block_word < 0) || (block_word > 0xFF) || (count_word < 0) ||
      ((uint16_t)count_word > MAX_BLOCK_WORDS) ||
      (((uint16_t)(position + 2u) + (uint16_t)count_word) > image_length) ||
      !BlockIndex(h, (uint8_t)block_word, &index) ||
      (WriteBlock(h, (uint8_t)block_word, &h->image_words[position + 2u], (uint8_t)count_word) !=
       FW_CONSTANTS_OK)) {
    return false;
  }
  *loaded_mask |= UINT32_C(1) << index;
  *next = (uint16_t)((position + 2u) + (uint16_t)count_word);
  return true;
}

// The image payload is a list of records [block id, word count, words...], one per block.
static void LoadCommittedConstants(FwMaintenanceHandler* h) {
  InitConstants(h);
  uint16_t image_length = 0u;
  if (fw_flash_load(h->flash,
                    h->identity.kind,
                    h->image_words,
                    (uint16_t)FW_FLASH_MAX_PAYLOAD_WORDS,
                    &image_length) != FW_FLASH_OK) {
    return;
  }
  uint32_t loaded_mask = 0u;
  uint16_t position = 0u;
  while ((uint16_t)(position + 2u) <= image_length) {
    if (!LoadRecord(h, position, image_length, &loaded_mask, &position)) {
      InitConstants(h);
      return;
    }
  }
  if ((position != image_length) || !IsCompleteSet(h, loaded_mask)) {
    InitConstants(h);
    return;
  }
  const FwFlashImageInfo info = fw_flash_inspect(h->flash, h->identity.kind);
  h->blocks_valid_mask = loaded_mask;
  h->constants_valid = true;
  h->constants_version = info.constants_version;
  h->constants_crc = info.image_crc;
}

void fw_maintenance_power_cycle(FwMaintenanceHandler* handler) {
  fw_decoder_init(&handler->decoder);
  handler->counters.requests_acked = 0u;
  handler->counters.requests_naked = 0u;
  for (uint8_t i = 0u; i < FW_RESULT_CODE_COUNT; ++i) {
    handler->counters.naks_by_code[i] = 0u;
  }
  handler->mode = 0u;
  handler->tag = 0u;
  handler->data_sequence = 0u;
  LoadCommittedConstants(handler);
}

void fw_maintenance_init(FwMaintenanceHandler* handler,
                         const FwUnitIdentity* identity,
                         FwFlashStore* flash) {
  handler->identity = *identity;
  handler->flash = flash;
  handler->frame.type = 0u;
  handler->frame.sequence = 0u;
  handler->frame.tag = 0u;
  handler->frame.payload_length = 0u;
  handler->data_length = 0u;
  fw_maintenance_power_cycle(handler);
}

uint8_t fw_maintenance_take_data_sequence(FwMaintenanceHandler* handler) {
  const uint8_t sequence = handler->data_sequence;
  handler->data_sequence = (uint8_t)(handler->data_sequence + 1u);
  return sequence;
}

static uint16_t Respond(FwMaintenanceHandler* h,
                        uint8_t command,
                        uint8_t sequence,
                        FwResultCode result,
                        uint8_t* response,
                        uint16_t response_capacity) {
  if (result == FW_RESULT_ACK) {
    ++h->counters.requests_acked;
  } else {
    h->data_length = 0u;
    ++h->counters.requests_naked;
    ++h->counters.naks_by_code[result];
  }
  uint8_t payload[FW_MAX_PAYLOAD_BYTES];
  payload[0] = command;
  payload[1] = (uint8_t)result;
  for (uint8_t i = 0u; i < h->data_length; ++i) {
    payload[2u + i] = h->data[i];
  }
  return fw_encode_frame((uint8_t)FW_PACKET_MAINTENANCE_RESPONSE,
                         sequence,
                         h->tag,
                         payload,
                         (uint8_t)(2u + h->data_length),
                         response,
                         response_capacity);
}

static FwResultCode DoSetMode(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != ONE_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  const uint8_t mode = frame->payload[1];
  const bool defined = IsImu(h) ? fw_is_imu_mode_byte(mode) : fw_is_ads_mode_byte(mode);
  if (!defined) {
    return FW_RESULT_BAD_ARGUMENT;
  }
  // Raw is 0 for both unit kinds; every other mode uses the constants.
  if ((mode != 0u) && !h->constants_valid) {
    return FW_RESULT_NO_VALID_CONSTANTS;
  }
  h->mode = mode;
  h->data[0] = h->mode;
  h->data_length = 1u;
  return FW_RESULT_ACK;
}

static FwResultCode DoSetTag(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != ONE_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  h->tag = frame->payload[1];
  h->data[0] = h->tag;
  h->data_length = 1u;
  return FW_RESULT_ACK;
}

FwResultCode fw_maintenance_write_block(FwMaintenanceHandler* handler,
                                        uint8_t block_id,
                                        const int16_t* words,
                                        uint8_t count) {
  uint8_t index = 0u;
  if (!BlockIndex(handler, block_id, &index)) {
    return FW_RESULT_UNKNOWN_BLOCK;
  }
  const FwConstantsStatus status = WriteBlock(handler, block_id, words, count);
  if (status != FW_CONSTANTS_OK) {
    return ToResultCode(status);
  }
  handler->blocks_valid_mask |= UINT32_C(1) << index;
  return FW_RESULT_ACK;
}

static FwResultCode DoWriteBlock(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length < WRITE_BLOCK_HEADER_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  const uint8_t block_id = frame->payload[1];
  const uint8_t word_count = frame->payload[2];
  if ((uint16_t)frame->payload_length !=
      (uint16_t)(WRITE_BLOCK_HEADER_BYTES + (2u * (uint16_t)word_count))) {
    return FW_RESULT_BAD_LENGTH;
  }
  uint8_t index = 0u;
  if (!BlockIndex(h, block_id, &index)) {
    return FW_RESULT_UNKNOWN_BLOCK;
  }
  int16_t words[MAX_BLOCK_WORDS];
  for (uint8_t i = 0u; i < word_count; ++i) {
    words[i] = fw_get_i16_le(&frame->payload[WRITE_BLOCK_HEADER_BYTES + (2u * i)]);
  }
  const FwResultCode result = fw_maintenance_write_block(h, block_id, words, word_count);
  if (result != FW_RESULT_ACK) {
    return result;
  }
  h->data[0] = block_id;
  h->data_length = 1u;
  return FW_RESULT_ACK;
}

static FwResultCode DoReadBlock(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != ONE_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  const uint8_t block_id = frame->payload[1];
  uint8_t index = 0u;
  if (!BlockIndex(h, block_id, &index)) {
    return FW_RESULT_UNKNOWN_BLOCK;
  }
  int16_t words[MAX_BLOCK_WORDS];
  uint8_t word_count = 0u;
  const FwConstantsStatus status =
      ReadBlock(h, block_id, words, (uint8_t)MAX_BLOCK_WORDS, &word_count);
  if (status != FW_CONSTANTS_OK) {
    return ToResultCode(status);
  }
  h->data[0] = block_id;
  h->data[1] = word_count;
  for (uint8_t i = 0u; i < word_count; ++i) {
    fw_put_i16_le(&h->data[2u + (2u * i)], words[i]);
  }
  h->data_length = (uint8_t)(2u + (2u * word_count));
  return FW_RESULT_ACK;
}

static FwResultCode DoCommit(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != NO_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  if (!IsCompleteSet(h, h->blocks_valid_mask)) {
    return FW_RESULT_INCOMPLETE_CONSTANTS;
  }
  uint16_t position = 0u;
  for (uint8_t i = 0u; i < BlockCount(h); ++i) {
    uint8_t word_count = 0u;
    const uint16_t free_words = (uint16_t)(FW_FLASH_MAX_PAYLOAD_WORDS - position);
    if (free_words < 2u) {
      return FW_RESULT_FLASH_ERROR;
    }
    const uint8_t capacity = ((uint16_t)(free_words - 2u) < MAX_BLOCK_WORDS)
                                 ? (uint8_t)(free_words - 2u)
                                 : (uint8_t)MAX_BLOCK_WORDS;
    if (ReadBlock(h, BlockIdAt(h, i), &h->image_words[position + 2u], capacity, &word_count) !=
        FW_CONSTANTS_OK) {
      return FW_RESULT_FLASH_ERROR;
    }
    h->image_words[position] = (int16_t)BlockIdAt(h, i);
    h->image_words[position + 1u] = (int16_t)word_count;
    position = (uint16_t)((position + 2u) + word_count);
  }
  if (fw_flash_commit(h->flash, h->identity.kind, h->image_words, position) != FW_FLASH_OK) {
    return FW_RESULT_FLASH_ERROR;
  }
  const FwFlashImageInfo info = fw_flash_inspect(h->flash, h->identity.kind);
  h->constants_valid = true;
  h->constants_version = info.constants_version;
  h->constants_crc = info.image_crc;
  fw_put_u16_le(&h->data[0], h->constants_version);
  fw_put_u16_le(&h->data[2], h->constants_crc);
  h->data_length = 4u;
  return FW_RESULT_ACK;
}

static FwResultCode DoIdentify(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != NO_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  h->data[0] = (uint8_t)h->identity.kind;
  fw_put_u32_le(&h->data[1], h->identity.serial_number);
  h->data[5] = h->identity.firmware_major;
  h->data[6] = h->identity.firmware_minor;
  h->data[7] = h->identity.firmware_patch;
  h->data[8] = h->constants_valid ? 1u : 0u;
  fw_put_u16_le(&h->data[9], h->constants_version);
  fw_put_u16_le(&h->data[11], h->constants_crc);
  h->data[13] = h->mode;
  h->data[14] = h->tag;
  h->data_length = 15u;
  return FW_RESULT_ACK;
}

static FwResultCode DoReset(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != NO_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  fw_maintenance_power_cycle(h);
  h->data[0] = h->constants_valid ? 1u : 0u;
  h->data_length = 1u;
  return FW_RESULT_ACK;
}

static FwResultCode DoReadCounters(FwMaintenanceHandler* h, const FwFrame* frame) {
  if (frame->payload_length != NO_ARGUMENT_REQUEST_BYTES) {
    return FW_RESULT_BAD_LENGTH;
  }
  const FwDecoderCounters* decoder = &h->decoder.counters;
  fw_put_u32_le(&h->data[0], decoder->frames_ok);
  fw_put_u32_le(&h->data[4], decoder->bad_crc);
  fw_put_u32_le(&h->data[8], decoder->bad_length);
  fw_put_u32_le(&h->data[12], decoder->unknown_type);
  fw_put_u32_le(&h->data[16], decoder->resync_bytes_skipped);
  fw_put_u32_le(&h->data[20], h->counters.requests_acked);
  fw_put_u32_le(&h->data[24], h->counters.requests_naked);
  h->data_length = 28u;
  return FW_RESULT_ACK;
}

uint16_t fw_maintenance_handle_request(FwMaintenanceHandler* handler,
                                       const FwFrame* frame,
                                       uint8_t* response,
                                       uint16_t response_capacity) {
  if ((frame->type != (uint8_t)FW_PACKET_MAINTENANCE_REQUEST) || (frame->payload_length < 1u) ||
      (response_capacity < FW_MAX_FRAME_BYTES)) {
    return 0u;
  }
  handler->data_length = 0u;
  const uint8_t command = frame->payload[0];
  FwResultCode result = FW_RESULT_UNKNOWN_COMMAND;
  switch (command) {
    case (uint8_t)FW_CMD_SET_MODE:
      result = DoSetMode(handler, frame);
      break;
    case (uint8_t)FW_CMD_SET_TAG:
      result = DoSetTag(handler, frame);
      break;
    case (uint8_t)FW_CMD_WRITE_BLOCK:
      result = DoWriteBlock(handler, frame);
      break;
    case (uint8_t)FW_CMD_READ_BLOCK:
      result = DoReadBlock(handler, frame);
      break;
    case (uint8_t)FW_CMD_COMMIT:
      result = DoCommit(handler, frame);
      break;
    case (uint8_t)FW_CMD_IDENTIFY:
      result = DoIdentify(handler, frame);
      break;
    case (uint8_t)FW_CMD_RESET:
      result = DoReset(handler, frame);
      break;
    case (uint8_t)FW_CMD_READ_COUNTERS:
      result = DoReadCounters(handler, frame);
      break;
    default:  // NONE and anything undefined
      result = FW_RESULT_UNKNOWN_COMMAND;
      break;
  }
  return Respond(handler, command, frame->sequence, result, response, response_capacity);
}

FwPortResult fw_maintenance_receive(FwMaintenanceHandler* handler,
                                    const uint8_t* bytes,
                                    uint16_t count,
                                    uint8_t* response,
                                    uint16_t response_capacity) {
  FwPortResult port;
  port.consumed_bytes = 0u;
  port.response_bytes = 0u;
  bool more = true;
  while (more) {
    // The rest of the chunk (never an offset from a null pointer when nothing is left).
    const uint8_t* rest = (port.consumed_bytes < count) ? &bytes[port.consumed_bytes] : bytes;
    const FwDecodeResult result = fw_decoder_feed(
        &handler->decoder, rest, (uint16_t)(count - port.consumed_bytes), &handler->frame);
    port.consumed_bytes = (uint16_t)(port.consumed_bytes + result.consumed_bytes);
    if (result.event == FW_DECODE_FRAME) {
      port.response_bytes =
          fw_maintenance_handle_request(handler, &handler->frame, response, response_capacity);
    } else if ((result.event == FW_DECODE_BAD_CRC) &&
               (handler->frame.type == (uint8_t)FW_PACKET_MAINTENANCE_REQUEST)) {
      port.response_bytes = Respond(handler,
                                    (uint8_t)FW_CMD_NONE,
                                    handler->frame.sequence,
                                    FW_RESULT_BAD_CRC,
                                    response,
                                    response_capacity);
    } else {
      // NEED_MORE_BYTES ends the chunk; a header error is only counted
    }
    more = (result.event != FW_DECODE_NEED_MORE_BYTES) && (port.response_bytes == 0u);
  }
  return port;
}
