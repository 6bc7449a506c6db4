#include "golden_replay.h"

#include <stdbool.h>
#include <stdint.h>

#include "firmware_model/target/adahrs_fw.h"
#include "firmware_model/target/ads_compensator.h"
#include "firmware_model/target/flash_store.h"
#include "firmware_model/target/imu_compensator.h"
#include "firmware_model/target/maintenance_handler.h"

// Bytes the maintenance port is offered at a time (a UART ISR hands over small chunks).
#define RX_CHUNK_BYTES 7u
// Bytes per transcript line of a frame dump (simavr prints UART lines of up to 255 characters).
#define HEX_BYTES_PER_LINE 32u

// The replay's set and the unit's state are never live at once: they share RAM (8 KB on the
// ATmega2560).
typedef struct {
  FwImuConstants imu;
  FwAdsConstants ads;
  FwAdsHysteresisState hysteresis;
} ReplaySet;

typedef struct {
  FwFlashStore flash;
  FwMaintenanceHandler port;
  AdahrsFwAdsState ads;
  uint8_t frame[FW_MAX_FRAME_BYTES];
} Unit;

static union {
  ReplaySet replay;
  Unit unit;
} g_state;

static uint16_t g_at;     // read position in the program
static uint16_t g_lines;  // transcript lines written

// ---- transcript

static void PutText(const char* text) {
  for (uint16_t i = 0u; text[i] != '\0'; ++i) {
    golden_replay_put_char(text[i]);
  }
}

static void PutHex(uint32_t value, uint8_t digits) {
  static const char kDigits[] = "0123456789abcdef";
  golden_replay_put_char(' ');
  for (uint8_t d = digits; d > 0u; --d) {
    golden_replay_put_char(kDigits[(value >> (4u * (uint8_t)(d - 1u))) & 0xFu]);
  }
}

static void PutDec(uint32_t value) {
  char digits[10];
  uint8_t n = 0u;
  uint32_t rest = value;
  do {
    digits[n] = (char)('0' + (char)(rest % 10u));
    rest /= 10u;
    ++n;
  } while (rest != 0u);
  golden_replay_put_char(' ');
  while (n > 0u) {
    --n;
    golden_replay_put_char(digits[n]);
  }
}

static void EndLine(void) {
  golden_replay_put_char('\n');
  ++g_lines;
}

void golden_replay_put_line_u32(const char* text, uint32_t value) {
  PutText(text);
  PutDec(value);
  EndLine();
}

// A frame as "<tag> <length>" then its bytes in hex, HEX_BYTES_PER_LINE to a line.
static void PutFrame(const char* tag, const uint8_t* bytes, uint16_t length) {
  golden_replay_put_line_u32(tag, length);
  for (uint16_t i = 0u; i < length; i += HEX_BYTES_PER_LINE) {
    PutText("  ");
    for (uint16_t k = i; (k < length) && (k < (uint16_t)(i + HEX_BYTES_PER_LINE)); ++k) {
      PutHex(bytes[k], 2u);
    }
    EndLine();
  }
}

// ---- program

static uint8_t NextU8(void) {
  const uint8_t b = golden_replay_program_byte(g_at);
  ++g_at;
  return b;
}

static uint16_t NextU16(void) {
  const uint16_t low = NextU8();
  return (uint16_t)(low | (uint16_t)((uint16_t)NextU8() << 8));
}

static uint32_t NextU32(void) {
  const uint32_t low = NextU16();
  return low | ((uint32_t)NextU16() << 16);
}

static int16_t NextI16(void) { return fw_s16_from_bits(NextU16()); }

static int32_t NextI32(void) { return fw_s32_from_bits(NextU32()); }

static void NextImuFrame(FwImuRawFrame* raw) {
  for (uint8_t i = 0u; i < 6u; ++i) {
    raw->t1_cnt[i] = NextU16();
  }
  for (uint8_t i = 0u; i < 6u; ++i) {
    raw->t2_cnt[i] = NextU16();
  }
  for (uint8_t i = 0u; i < 3u; ++i) {
    raw->gyro_cnt[i] = NextI32();
  }
  for (uint8_t i = 0u; i < 3u; ++i) {
    raw->temp_cnt[i] = NextU16();
  }
}

static void NextAdsFrame(FwAdsRawFrame* raw) {
  raw->ps_cnt = NextI32();
  raw->pt_cnt = NextI32();
  raw->ps_bridge_cnt = NextI32();
  raw->pt_bridge_cnt = NextI32();
  raw->oat_cnt = NextI32();
}

// ---- steps

static void StepBlock(void) {
  const uint8_t unit = NextU8();
  const uint8_t id = NextU8();
  const uint8_t count = NextU8();
  int16_t words[FW_ADS_MAX_BLOCK_WORDS];
  for (uint8_t i = 0u; i < count; ++i) {
    words[i] = NextI16();
  }
  const FwConstantsStatus status =
      (unit == 0u) ? fw_imu_constants_write_block(&g_state.replay.imu, id, words, count)
                   : fw_ads_constants_write_block(&g_state.replay.ads, id, words, count);
  PutText("blk");
  PutDec(unit);
  PutHex(id, 2u);
  PutDec((uint32_t)status);
  EndLine();
}

static void PutOutputs(const char* tag,
                       uint16_t frame,
                       uint8_t mode,
                       uint16_t flags,
                       uint32_t cycles,
                       const int32_t* values,
                       uint8_t count) {
  PutText(tag);
  PutDec(frame);
  PutDec(mode);
  PutHex(flags, 4u);
  PutDec(cycles);
  for (uint8_t i = 0u; i < count; ++i) {
    PutHex((uint32_t)values[i], 8u);
  }
  EndLine();
}

static void StepImuReplay(uint16_t frame) {
  FwImuRawFrame raw;
  NextImuFrame(&raw);
  for (uint8_t mode = 0u; mode <= 3u; ++mode) {
    FwDspEngine engine;
    fw_dsp_init(&engine, fw_dsp_config_default());
    FwImuCompensatedFrame out;
    fw_imu_compensate(&engine, &g_state.replay.imu, (FwImuMode)mode, &raw, &out);
    PutOutputs("imu", frame, mode, out.flags, engine.cycles, out.value, FW_IMU_OUTPUT_VALUES);
  }
}

static void StepAdsReplay(uint16_t frame) {
  FwAdsRawFrame raw;
  NextAdsFrame(&raw);
  for (uint8_t mode = 0u; mode <= 1u; ++mode) {
    FwDspEngine engine;
    fw_dsp_init(&engine, fw_dsp_config_default());
    FwAdsCompensatedFrame out;
    fw_ads_compensate(
        &engine, &g_state.replay.ads, (FwAdsMode)mode, &raw, &g_state.replay.hysteresis, &out);
    PutOutputs("ads", frame, mode, out.flags, engine.cycles, out.value, FW_ADS_OUTPUT_VALUES);
  }
}

static void StepPowerOn(void) {
  const uint8_t kind = NextU8();
  FwUnitIdentity identity;
  identity.kind = (kind == (uint8_t)FW_UNIT_IMU) ? FW_UNIT_IMU : FW_UNIT_ADS;
  identity.serial_number = UINT32_C(0x00C0FFEE);
  identity.firmware_major = 1u;
  identity.firmware_minor = 2u;
  identity.firmware_patch = 3u;
  fw_flash_erase(&g_state.unit.flash);
  adahrs_fw_power_on(&g_state.unit.port, &g_state.unit.ads, &identity, &g_state.unit.flash);
  golden_replay_put_line_u32("pwr", kind);
}

static void StepReceive(void) {
  uint16_t length = NextU16();
  uint8_t chunk[RX_CHUNK_BYTES];
  while (length > 0u) {
    const uint16_t count = (length < RX_CHUNK_BYTES) ? length : (uint16_t)RX_CHUNK_BYTES;
    for (uint16_t i = 0u; i < count; ++i) {
      chunk[i] = NextU8();
    }
    length = (uint16_t)(length - count);
    uint16_t offered = 0u;
    bool more = true;
    while (more) {
      const FwPortResult result = adahrs_fw_receive(&g_state.unit.port,
                                                    &chunk[offered],
                                                    (uint16_t)(count - offered),
                                                    g_state.unit.frame,
                                                    (uint16_t)FW_MAX_FRAME_BYTES);
      offered = (uint16_t)(offered + result.consumed_bytes);
      if (result.response_bytes != 0u) {
        PutFrame("rsp", g_state.unit.frame, result.response_bytes);
      }
      more = (result.response_bytes != 0u);
    }
  }
}

static void StepImuSample(void) {
  FwImuRawFrame raw;
  NextImuFrame(&raw);
  FwDspEngine engine;
  fw_dsp_init(&engine, fw_dsp_config_default());
  const uint16_t length = adahrs_fw_imu_sample(
      &g_state.unit.port, &engine, &raw, g_state.unit.frame, (uint16_t)FW_MAX_FRAME_BYTES);
  PutFrame("dat", g_state.unit.frame, length);
}

static void StepAdsSample(void) {
  FwAdsRawFrame raw;
  NextAdsFrame(&raw);
  FwDspEngine engine;
  fw_dsp_init(&engine, fw_dsp_config_default());
  const uint16_t length = adahrs_fw_ads_sample(&g_state.unit.port,
                                               &g_state.unit.ads,
                                               &engine,
                                               &raw,
                                               g_state.unit.frame,
                                               (uint16_t)FW_MAX_FRAME_BYTES);
  PutFrame("dat", g_state.unit.frame, length);
}

uint16_t golden_replay_run(void) {
  g_at = 0u;
  g_lines = 0u;
  uint16_t imu_frame = 0u;
  uint16_t ads_frame = 0u;
  bool running = true;
  while (running) {
    const uint8_t step = NextU8();
    switch (step) {
      case (uint8_t)'S':
        golden_replay_put_line_u32("set", NextU8());
        fw_imu_constants_init(&g_state.replay.imu);
        fw_ads_constants_init(&g_state.replay.ads);
        imu_frame = 0u;
        ads_frame = 0u;
        break;
      case (uint8_t)'B':
        StepBlock();
        break;
      case (uint8_t)'F':
        StepImuReplay(imu_frame);
        ++imu_frame;
        break;
      case (uint8_t)'H':
        fw_ads_hysteresis_reset(&g_state.replay.hysteresis);
        break;
      case (uint8_t)'G':
        StepAdsReplay(ads_frame);
        ++ads_frame;
        break;
      case (uint8_t)'P':
        StepPowerOn();
        break;
      case (uint8_t)'R':
        StepReceive();
        break;
      case (uint8_t)'I':
        StepImuSample();
        break;
      case (uint8_t)'A':
        StepAdsSample();
        break;
      default:  // 'E', or a byte the program does not define
        golden_replay_put_line_u32("end", step);
        running = false;
        break;
    }
  }
  return g_lines;
}
