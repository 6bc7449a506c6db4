// The unit's firmware (target/, C99, fw_ names) as the host's C++ sees it: the names of namespace
// adahrs::firmware_model, references for read-only arguments, enum classes for the protocol's
// codes, and classes for the objects with state (DspEngine, PacketDecoder, FlashStore,
// MaintenanceHandler). Every function is a thin inline call through the C API (extern "C"), so the
// rig's units, the pipeline and the tests run exactly the code the dsPIC runs.
// Plain data types are the C structs themselves (ImuConstants is FwImuConstants, ...); the few C
// structs that hold a code as a C enum have a C++ twin here with the enum class (ImuDataPayload,
// UnitIdentity, DecodeResult, FlashImageInfo, DspConfig with the reset defaults).
// Left out: the MPLAB API of adahrs_fw.h (the rig calls it directly).
#pragma once

#include <cstdint>

#include "common/unit_kind.h"
#include "firmware_model/target/adahrs_fw.h"
#include "firmware_model/target/ads_compensator.h"
#include "firmware_model/target/ads_constants.h"
#include "firmware_model/target/air_data_law.h"
#include "firmware_model/target/air_data_tables.h"
#include "firmware_model/target/bridge_linearisation.h"
#include "firmware_model/target/byte_order.h"
#include "firmware_model/target/compensated_frame.h"
#include "firmware_model/target/crc16.h"
#include "firmware_model/target/data_payloads.h"
#include "firmware_model/target/dsp_engine.h"
#include "firmware_model/target/fixed_coeff.h"
#include "firmware_model/target/flash_store.h"
#include "firmware_model/target/imu_compensator.h"
#include "firmware_model/target/imu_constants.h"
#include "firmware_model/target/maintenance_handler.h"
#include "firmware_model/target/packet_codec.h"
#include "firmware_model/target/preisach_q15.h"
#include "firmware_model/target/q31_kernels.h"
#include "firmware_model/target/q_math.h"
#include "firmware_model/target/unit_protocol.h"

namespace adahrs::firmware_model {

// ---- q_math.h
inline constexpr int64_t kAcc40Max = FW_ACC40_MAX;
inline constexpr int64_t kAcc40Min = FW_ACC40_MIN;
inline constexpr int64_t kAcc31Max = FW_ACC31_MAX;
inline constexpr int64_t kAcc31Min = FW_ACC31_MIN;
inline constexpr int16_t kQ15Max = INT16_MAX;
inline constexpr int16_t kQ15Min = INT16_MIN;
inline int64_t SignExtend40(int64_t v) { return fw_sign_extend40(v); }
inline int64_t Clamp64(int64_t v, int64_t lo, int64_t hi, bool* clipped) {
  return fw_clamp64(v, lo, hi, clipped);
}
inline int16_t SatQ15(int64_t v) { return fw_sat_q15(v); }
inline int32_t SatQ31(int64_t v) { return fw_sat_q31(v); }
inline int64_t ShiftArith(int64_t v, int32_t shift) {
  return fw_shift_arith(v, static_cast<int8_t>(shift));
}
inline int64_t RoundHighWord(int64_t acc40, bool convergent) {
  return fw_round_high_word(acc40, convergent);
}
inline int16_t HighWord(int32_t v) { return fw_high_word(v); }
inline uint16_t LowWord(int32_t v) { return fw_low_word(v); }
inline int32_t JoinWords(int16_t high, uint16_t low) { return fw_join_words(high, low); }

// ---- byte_order.h
inline void PutU16Le(uint8_t* out, uint16_t value) { fw_put_u16_le(out, value); }
inline void PutU32Le(uint8_t* out, uint32_t value) { fw_put_u32_le(out, value); }
inline void PutI16Le(uint8_t* out, int16_t value) { fw_put_i16_le(out, value); }
inline void PutI32Le(uint8_t* out, int32_t value) { fw_put_i32_le(out, value); }
inline uint16_t GetU16Le(const uint8_t* in) { return fw_get_u16_le(in); }
inline uint32_t GetU32Le(const uint8_t* in) { return fw_get_u32_le(in); }
inline int16_t GetI16Le(const uint8_t* in) { return fw_get_i16_le(in); }
inline int32_t GetI32Le(const uint8_t* in) { return fw_get_i32_le(in); }

// ---- crc16.h
inline constexpr uint16_t kCrc16Init = FW_CRC16_INIT;
inline uint16_t Crc16Update(uint16_t crc, const uint8_t* bytes, uint16_t count) {
  return fw_crc16_update(crc, bytes, count);
}
inline uint16_t Crc16CcittFalse(const uint8_t* bytes, uint16_t count) {
  return fw_crc16_ccitt_false(bytes, count);
}

// ---- compensated_frame.h
enum class ImuCompensationMode : uint8_t {
  kRaw = FW_IMU_MODE_RAW,
  kThermal = FW_IMU_MODE_THERMAL,
  kSensorCalibrated = FW_IMU_MODE_SENSOR_CALIBRATED,
  kFullyCalibrated = FW_IMU_MODE_FULLY_CALIBRATED,
};
enum class AdsCompensationMode : uint8_t {
  kRaw = FW_ADS_MODE_RAW,
  kSurface = FW_ADS_MODE_SURFACE,
};
using ImuRawFrame = FwImuRawFrame;
using AdsRawFrame = FwAdsRawFrame;
using ImuCompensatedFrame = FwImuCompensatedFrame;
using AdsCompensatedFrame = FwAdsCompensatedFrame;
inline constexpr uint8_t kImuOutputValues = FW_IMU_OUTPUT_VALUES;
inline constexpr uint8_t kAdsOutputValues = FW_ADS_OUTPUT_VALUES;
enum CompensationFlag : uint16_t {
  kFlagInputSaturated = FW_FLAG_INPUT_SATURATED,
  kFlagOutputSaturated = FW_FLAG_OUTPUT_SATURATED,
  kFlagBadDuty = FW_FLAG_BAD_DUTY,
};

// ---- unit_protocol.h
inline constexpr uint8_t kSyncByte0 = FW_SYNC_BYTE0;
inline constexpr uint8_t kSyncByte1 = FW_SYNC_BYTE1;
inline constexpr uint16_t kFrameHeaderBytes = FW_FRAME_HEADER_BYTES;
inline constexpr uint16_t kFrameTrailerBytes = FW_FRAME_TRAILER_BYTES;
inline constexpr uint16_t kMaxPayloadBytes = FW_MAX_PAYLOAD_BYTES;
inline constexpr uint16_t kMaxFrameBytes = FW_MAX_FRAME_BYTES;
enum class PacketType : uint8_t {
  kImuData = FW_PACKET_IMU_DATA,
  kAdsData = FW_PACKET_ADS_DATA,
  kMaintenanceRequest = FW_PACKET_MAINTENANCE_REQUEST,
  kMaintenanceResponse = FW_PACKET_MAINTENANCE_RESPONSE,
};
using common::UnitKind;  // the firmware's FwUnitKind codes, checked here:
static_assert(static_cast<uint8_t>(UnitKind::kImu) == FW_UNIT_IMU);
static_assert(static_cast<uint8_t>(UnitKind::kAds) == FW_UNIT_ADS);
inline constexpr uint8_t kImuRawPayloadBytes = FW_IMU_RAW_PAYLOAD_BYTES;
inline constexpr uint8_t kImuCompensatedPayloadBytes = FW_IMU_COMPENSATED_PAYLOAD_BYTES;
inline constexpr uint8_t kAdsRawPayloadBytes = FW_ADS_RAW_PAYLOAD_BYTES;
inline constexpr uint8_t kAdsCompensatedPayloadBytes = FW_ADS_COMPENSATED_PAYLOAD_BYTES;
enum class MaintenanceCommand : uint8_t {
  kNone = FW_CMD_NONE,
  kSetMode = FW_CMD_SET_MODE,
  kSetTag = FW_CMD_SET_TAG,
  kWriteBlock = FW_CMD_WRITE_BLOCK,
  kReadBlock = FW_CMD_READ_BLOCK,
  kCommit = FW_CMD_COMMIT,
  kIdentify = FW_CMD_IDENTIFY,
  kReset = FW_CMD_RESET,
  kReadCounters = FW_CMD_READ_COUNTERS,
};
enum class ResultCode : uint8_t {
  kAck = FW_RESULT_ACK,
  kBadCrc = FW_RESULT_BAD_CRC,
  kBadLength = FW_RESULT_BAD_LENGTH,
  kUnknownCommand = FW_RESULT_UNKNOWN_COMMAND,
  kBadArgument = FW_RESULT_BAD_ARGUMENT,
  kNoValidConstants = FW_RESULT_NO_VALID_CONSTANTS,
  kUnknownBlock = FW_RESULT_UNKNOWN_BLOCK,
  kBlockWrongLength = FW_RESULT_BLOCK_WRONG_LENGTH,
  kConstantOutOfRange = FW_RESULT_CONSTANT_OUT_OF_RANGE,
  kConstantOverflow = FW_RESULT_CONSTANT_OVERFLOW,
  kIncompleteConstants = FW_RESULT_INCOMPLETE_CONSTANTS,
  kFlashError = FW_RESULT_FLASH_ERROR,
};
inline constexpr uint8_t kResultCodeCount = FW_RESULT_CODE_COUNT;

// ---- fixed_coeff.h
enum class ConstantsStatus : uint8_t {
  kOk = FW_CONSTANTS_OK,
  kUnknownBlock = FW_CONSTANTS_UNKNOWN_BLOCK,
  kWrongLength = FW_CONSTANTS_WRONG_LENGTH,
  kOutOfRange = FW_CONSTANTS_OUT_OF_RANGE,
  kWouldOverflow = FW_CONSTANTS_WOULD_OVERFLOW,
  kNullArgument = FW_CONSTANTS_NULL_ARGUMENT,
};
inline ConstantsStatus ToCxx(FwConstantsStatus s) { return static_cast<ConstantsStatus>(s); }
using CoeffQ31 = FwCoeffQ31;
using InputNormQ31 = FwInputNormQ31;
using PolyQ31 = FwPolyQ31;
inline constexpr uint8_t kMaxPolyDegree = FW_MAX_POLY_DEGREE;
inline constexpr int8_t kMinExponent = FW_MIN_EXPONENT;
inline constexpr int8_t kMaxExponent = FW_MAX_EXPONENT;
inline constexpr int8_t kMaxAlignShift = FW_MAX_ALIGN_SHIFT;
inline constexpr uint8_t kCoeffWords = FW_COEFF_WORDS;
inline constexpr uint8_t kNormWords = FW_NORM_WORDS;
constexpr uint8_t PolyWords(uint8_t degree) { return static_cast<uint8_t>(FW_POLY_WORDS(degree)); }
inline ConstantsStatus CoeffFromWords(const int16_t* words, CoeffQ31* coeff) {
  return ToCxx(fw_coeff_from_words(words, coeff));
}
inline void CoeffToWords(const CoeffQ31& coeff, int16_t* words) {
  fw_coeff_to_words(&coeff, words);
}
inline ConstantsStatus NormFromWords(const int16_t* words, uint8_t max_shift, InputNormQ31* norm) {
  return ToCxx(fw_norm_from_words(words, max_shift, norm));
}
inline void NormToWords(const InputNormQ31& norm, int16_t* words) {
  fw_norm_to_words(&norm, words);
}
inline ConstantsStatus PolyFromWords(const int16_t* words, uint8_t degree, PolyQ31* poly) {
  return ToCxx(fw_poly_from_words(words, degree, poly));
}
inline void PolyToWords(const PolyQ31& poly, uint8_t degree, int16_t* words) {
  fw_poly_to_words(&poly, degree, words);
}
inline ConstantsStatus ValidatePoly(const PolyQ31& poly, uint8_t degree) {
  return ToCxx(fw_validate_poly(&poly, degree));
}

// ---- dsp_engine.h
enum class Acc : uint8_t { kA = FW_ACC_A, kB = FW_ACC_B };
constexpr Acc Other(Acc acc) { return acc == Acc::kA ? Acc::kB : Acc::kA; }
inline FwAcc ToC(Acc acc) { return static_cast<FwAcc>(acc); }

enum class DspOp : uint8_t {
  kMpy = FW_OP_MPY,
  kMac = FW_OP_MAC,
  kMsc = FW_OP_MSC,
  kLac = FW_OP_LAC,
  kSac = FW_OP_SAC,
  kSacR = FW_OP_SAC_R,
  kSftac = FW_OP_SFTAC,
  kAddAcc = FW_OP_ADD_ACC,
  kSubAcc = FW_OP_SUB_ACC,
  kNegAcc = FW_OP_NEG_ACC,
  kAddWordAcc = FW_OP_ADD_WORD_ACC,
  kClrAcc = FW_OP_CLR_ACC,
  kMovAccWord = FW_OP_MOV_ACC_WORD,
  kMulSS = FW_OP_MUL_SS,
  kMulSU = FW_OP_MUL_SU,
  kMulUU = FW_OP_MUL_UU,
  kDivF = FW_OP_DIV_F,
  kDivSD = FW_OP_DIV_SD,
  kDivUD = FW_OP_DIV_UD,
  kMov = FW_OP_MOV,
  kAlu = FW_OP_ALU,
  kBranch = FW_OP_BRANCH,
  kCall = FW_OP_CALL,
  kReturn = FW_OP_RETURN,
  kCount = FW_OP_COUNT
};
inline uint8_t DspOpCycles(DspOp op) { return fw_dsp_op_cycles(static_cast<FwDspOp>(op)); }
inline const char* DspOpName(DspOp op) { return fw_dsp_op_name(static_cast<FwDspOp>(op)); }

/// CORCON bits (FwDspConfig), defaulting to the compensator's configuration.
struct DspConfig {
  bool integer_mode = false;        ///< IF: 1 = integer, 0 = fractional (product << 1)
  bool unsigned_mode = false;       ///< US: operands of MPY/MAC unsigned
  bool saturate_a = true;           ///< SATA
  bool saturate_b = true;           ///< SATB
  bool super_saturation = false;    ///< ACCSAT: 1 = bit-39 (9.31), 0 = bit-31 (1.31)
  bool saturate_writes = true;      ///< SATDW
  bool convergent_rounding = true;  ///< RND: 0 = convergent (reset default), 1 = conventional

  FwDspConfig ToC() const {
    return FwDspConfig{integer_mode,
                       unsigned_mode,
                       saturate_a,
                       saturate_b,
                       super_saturation,
                       saturate_writes,
                       convergent_rounding};
  }
  static DspConfig FromC(const FwDspConfig& c) {
    return DspConfig{c.integer_mode,
                     c.unsigned_mode,
                     c.saturate_a,
                     c.saturate_b,
                     c.super_saturation,
                     c.saturate_writes,
                     c.convergent_rounding};
  }
};

using DivResult = FwDivResult;

/// The engine (FwDspEngine) with one method per instruction.
class DspEngine {
 public:
  DspEngine() { fw_dsp_init(&c_, DspConfig{}.ToC()); }
  explicit DspEngine(const DspConfig& config) { fw_dsp_init(&c_, config.ToC()); }

  DspConfig config() const { return DspConfig::FromC(c_.config); }
  void set_config(const DspConfig& config) { c_.config = config.ToC(); }

  void Mpy(Acc acc, int16_t a, int16_t b) { fw_dsp_mpy(&c_, ToC(acc), a, b); }
  void Mac(Acc acc, int16_t a, int16_t b) { fw_dsp_mac(&c_, ToC(acc), a, b); }
  void Msc(Acc acc, int16_t a, int16_t b) { fw_dsp_msc(&c_, ToC(acc), a, b); }
  void Lac(Acc acc, int16_t word, int8_t shift) { fw_dsp_lac(&c_, ToC(acc), word, shift); }
  int16_t Sac(Acc acc, int8_t shift) { return fw_dsp_sac(&c_, ToC(acc), shift); }
  int16_t SacR(Acc acc, int8_t shift) { return fw_dsp_sac_r(&c_, ToC(acc), shift); }
  void Sftac(Acc acc, int8_t shift) { fw_dsp_sftac(&c_, ToC(acc), shift); }
  void AddAcc(Acc dst) { fw_dsp_add_acc(&c_, ToC(dst)); }
  void SubAcc(Acc dst) { fw_dsp_sub_acc(&c_, ToC(dst)); }
  void NegAcc(Acc acc) { fw_dsp_neg_acc(&c_, ToC(acc)); }
  void AddWordAcc(Acc acc, int16_t word, int8_t shift) {
    fw_dsp_add_word_acc(&c_, ToC(acc), word, shift);
  }
  void ClrAcc(Acc acc) { fw_dsp_clr_acc(&c_, ToC(acc)); }

  void MovToAccLow(Acc acc, uint16_t word) { fw_dsp_mov_to_acc_low(&c_, ToC(acc), word); }
  void MovToAccHigh(Acc acc, int16_t word) { fw_dsp_mov_to_acc_high(&c_, ToC(acc), word); }
  uint16_t MovFromAccLow(Acc acc) { return fw_dsp_mov_from_acc_low(&c_, ToC(acc)); }
  int16_t MovFromAccHigh(Acc acc) { return fw_dsp_mov_from_acc_high(&c_, ToC(acc)); }
  int16_t MovFromAccUpper(Acc acc) { return fw_dsp_mov_from_acc_upper(&c_, ToC(acc)); }

  int32_t MulSS(int16_t a, int16_t b) { return fw_dsp_mul_ss(&c_, a, b); }
  int32_t MulSU(int16_t a, uint16_t b) { return fw_dsp_mul_su(&c_, a, b); }
  uint32_t MulUU(uint16_t a, uint16_t b) { return fw_dsp_mul_uu(&c_, a, b); }
  DivResult DivF(int16_t num, int16_t den) { return fw_dsp_div_f(&c_, num, den); }
  DivResult DivSD(int32_t num, int16_t den) { return fw_dsp_div_sd(&c_, num, den); }
  DivResult DivUD(uint32_t num, uint16_t den) { return fw_dsp_div_ud(&c_, num, den); }

  void ChargeMov(uint8_t count = 1) { fw_dsp_charge_mov(&c_, count); }
  void ChargeAlu(uint8_t count = 1) { fw_dsp_charge_alu(&c_, count); }
  void ChargeBranch(uint8_t count = 1) { fw_dsp_charge_branch(&c_, count); }
  void ChargeCallReturn() { fw_dsp_charge_call_return(&c_); }

  int64_t acc(Acc acc) const { return c_.acc[ToC(acc)]; }
  /// Sets an accumulator directly (test set-up; no cycles).
  void set_acc(Acc acc, int64_t value40) { c_.acc[ToC(acc)] = value40; }
  bool sa() const { return c_.sa; }
  bool sb() const { return c_.sb; }
  bool oa() const { return fw_dsp_overflowed31(&c_, FW_ACC_A); }
  bool ob() const { return fw_dsp_overflowed31(&c_, FW_ACC_B); }
  bool math_error() const { return c_.math_error; }
  bool TestAndClearSaturation() { return fw_dsp_test_and_clear_saturation(&c_); }

  uint32_t cycles() const { return c_.cycles; }
  uint32_t instructions() const { return c_.instructions; }
  uint32_t op_count(DspOp op) const { return c_.op_counts[static_cast<uint8_t>(op)]; }
  void ResetCounters() { fw_dsp_reset_counters(&c_); }

  /// The C engine, for calls into the C API.
  FwDspEngine* c() { return &c_; }
  const FwDspEngine* c() const { return &c_; }

 private:
  FwDspEngine c_;
};

// ---- q31_kernels.h
inline void LoadQ31(DspEngine* engine, Acc acc, int32_t v) {
  fw_load_q31(engine->c(), ToC(acc), v);
}
inline int32_t ReadQ31(DspEngine* engine, Acc acc) { return fw_read_q31(engine->c(), ToC(acc)); }
inline void SftacBy(DspEngine* engine, Acc acc, int32_t shift) {
  fw_sftac_by(engine->c(), ToC(acc), static_cast<int16_t>(shift));
}
inline void ShiftAcc(DspEngine* engine, Acc acc, int32_t shift) {
  fw_shift_acc(engine->c(), ToC(acc), static_cast<int16_t>(shift));
}
inline void MulQ31(DspEngine* engine, Acc acc, int32_t a_q31, int32_t b_q31) {
  fw_mul_q31(engine->c(), ToC(acc), a_q31, b_q31);
}
inline int32_t NormaliseQ31(DspEngine* engine,
                            int32_t v,
                            int8_t v_exponent,
                            const InputNormQ31& norm) {
  return fw_normalise_q31(engine->c(), v, v_exponent, &norm);
}
inline int32_t HornerQ31(
    DspEngine* engine, Acc acc, const PolyQ31& poly, uint8_t degree, int32_t x_q31) {
  return fw_horner_q31(engine->c(), ToC(acc), &poly, degree, x_q31);
}
inline uint16_t IntegerSqrt(DspEngine* engine, uint32_t radicand) {
  return fw_integer_sqrt(engine->c(), radicand);
}

// ---- preisach_q15.h
inline constexpr uint8_t kPreisachDepth = FW_PREISACH_DEPTH;
using BranchStartQ15 = FwBranchStartQ15;
using PreisachQ15 = FwPreisachQ15;
inline void PreisachResetQ15(PreisachQ15* op) { fw_preisach_reset_q15(op); }
inline int16_t PreisachUpdateQ15(DspEngine* engine,
                                 PreisachQ15* op,
                                 int32_t input,
                                 int8_t input_exponent,
                                 const CoeffQ31& inv_span) {
  return fw_preisach_update_q15(engine->c(), op, input, input_exponent, &inv_span);
}

// ---- bridge_linearisation.h
inline constexpr uint8_t kBridgeLinearisationWords = FW_BRIDGE_LINEARISATION_WORDS;
using BridgeLinearisationQ = FwBridgeLinearisationQ;
inline int32_t LinearisedBridgeCode(DspEngine* engine,
                                    const BridgeLinearisationQ& linearisation,
                                    int32_t y_code,
                                    uint16_t* flags) {
  return fw_linearised_bridge_code(engine->c(), &linearisation, y_code, flags);
}
inline ConstantsStatus BridgeLinearisationFromWords(const int16_t* words,
                                                    BridgeLinearisationQ* out) {
  return ToCxx(fw_bridge_linearisation_from_words(words, out));
}
inline void BridgeLinearisationToWords(const BridgeLinearisationQ& linearisation, int16_t* words) {
  fw_bridge_linearisation_to_words(&linearisation, words);
}

// ---- air_data_tables.h, air_data_law.h
inline constexpr int8_t kPressureExponent = FW_PRESSURE_EXPONENT;
inline constexpr int8_t kCasSquaredExponent = FW_CAS_SQUARED_EXPONENT;
inline constexpr uint8_t kIsaTableStepLog2 = FW_ISA_TABLE_STEP_LOG2;
inline constexpr uint16_t kIsaTableEntries = FW_ISA_TABLE_ENTRIES;
inline constexpr uint16_t kIsaFirstValidEntry = FW_ISA_FIRST_VALID_ENTRY;
inline constexpr uint8_t kCasTableStepLog2 = FW_CAS_TABLE_STEP_LOG2;
inline constexpr uint16_t kCasTableEntries = FW_CAS_TABLE_ENTRIES;
inline constexpr uint16_t kCasLastValidEntry = FW_CAS_LAST_VALID_ENTRY;
inline constexpr const int32_t* kIsaAltitudeTableQ31 = fw_isa_altitude_table_q31;
inline constexpr const int32_t* kCasSquaredTableQ31 = fw_cas_squared_table_q31;
enum AdsSurfaceLaw : uint8_t {
  kAdsLawDirect = FW_ADS_LAW_DIRECT,
  kAdsLawIsaAltitude = FW_ADS_LAW_ISA_ALTITUDE,
  kAdsLawCas = FW_ADS_LAW_CAS,
};
inline int32_t IsaAltitudeQ31(DspEngine* engine, int32_t ps_q31, uint16_t* flags) {
  return fw_isa_altitude_q31(engine->c(), ps_q31, flags);
}
inline int32_t CasQ31(DspEngine* engine, int32_t qc_q31, uint16_t* flags) {
  return fw_cas_q31(engine->c(), qc_q31, flags);
}

// ---- imu_constants.h
inline constexpr uint8_t kAccelChannels = FW_ACCEL_CHANNELS;
inline constexpr uint8_t kGyroChannels = FW_GYRO_CHANNELS;
inline constexpr uint8_t kImuChannels = FW_IMU_CHANNELS;
inline constexpr uint8_t kTempSensors = FW_TEMP_SENSORS;
inline constexpr int8_t kDutyExponent = FW_DUTY_EXPONENT;
inline constexpr int8_t kGyroCountExponent = FW_GYRO_COUNT_EXPONENT;
inline constexpr int8_t kTempCountExponent = FW_TEMP_COUNT_EXPONENT;
inline constexpr int8_t kAccelGExponent = FW_ACCEL_G_EXPONENT;
inline constexpr int8_t kAccelMps2Exponent = FW_ACCEL_MPS2_EXPONENT;
inline constexpr int8_t kRateExponent = FW_RATE_EXPONENT;
inline constexpr int8_t kScaleFactorExponent = FW_SCALE_FACTOR_EXPONENT;
inline constexpr int32_t kRatedAccel_g = FW_RATED_ACCEL_G;
inline constexpr int32_t kRatedRate_dps = FW_RATED_RATE_DPS;
inline constexpr int32_t kRatedAccel_mps2 = FW_RATED_ACCEL_MPS2;
inline constexpr uint8_t kImuThermalDegree = FW_IMU_THERMAL_DEGREE;
inline constexpr uint8_t kImuScaleFactorDegree = FW_IMU_SCALE_FACTOR_DEGREE;
using ThermalConstantsQ31 = FwThermalConstantsQ31;
using AccelScaleConstantsQ31 = FwAccelScaleConstantsQ31;
using GyroCubicConstantsQ31 = FwGyroCubicConstantsQ31;
using ScaleDeltaQ15 = FwScaleDeltaQ15;
using GSensitivityQ15 = FwGSensitivityQ15;
using ScaleTemperatureConstantsQ31 = FwScaleTemperatureConstantsQ31;
using ImuConstants = FwImuConstants;
enum ImuBlockId : uint8_t {
  kImuBlockThermalFirst = FW_IMU_BLOCK_THERMAL_FIRST,
  kImuBlockThermalLast = FW_IMU_BLOCK_THERMAL_LAST,
  kImuBlockAccelOffsetScale = FW_IMU_BLOCK_ACCEL_OFFSET_SCALE,
  kImuBlockGyroCubicFirst = FW_IMU_BLOCK_GYRO_CUBIC_FIRST,
  kImuBlockGyroCubicLast = FW_IMU_BLOCK_GYRO_CUBIC_LAST,
  kImuBlockCa = FW_IMU_BLOCK_CA,
  kImuBlockCg = FW_IMU_BLOCK_CG,
  kImuBlockScaleSwitch = FW_IMU_BLOCK_SCALE_SWITCH,
  kImuBlockScaleFactorFirst = FW_IMU_BLOCK_SCALE_FACTOR_FIRST,
  kImuBlockScaleFactorLast = FW_IMU_BLOCK_SCALE_FACTOR_LAST,
  kImuBlockAccelQuadratic = FW_IMU_BLOCK_ACCEL_QUADRATIC,
  kImuBlockGs = FW_IMU_BLOCK_GS,
};
inline constexpr uint8_t kImuBlockLast = FW_IMU_BLOCK_LAST;
inline constexpr uint8_t kImuThermalBlockWords = FW_IMU_THERMAL_BLOCK_WORDS;
inline constexpr uint8_t kImuAccelBlockWords = FW_IMU_ACCEL_BLOCK_WORDS;
inline constexpr uint8_t kImuGyroBlockWords = FW_IMU_GYRO_BLOCK_WORDS;
inline constexpr uint8_t kImuMatrixBlockWords = FW_IMU_MATRIX_BLOCK_WORDS;
inline constexpr uint8_t kImuScaleSwitchBlockWords = FW_IMU_SCALE_SWITCH_BLOCK_WORDS;
inline constexpr uint8_t kImuScaleFactorBlockWords = FW_IMU_SCALE_FACTOR_BLOCK_WORDS;
inline constexpr uint8_t kImuAccelQuadraticBlockWords = FW_IMU_ACCEL_QUADRATIC_BLOCK_WORDS;
inline constexpr uint8_t kImuMaxBlockWords = FW_IMU_MAX_BLOCK_WORDS;
inline void DeriveThermalAligned(ThermalConstantsQ31* thermal) {
  fw_derive_thermal_aligned(thermal);
}
inline void DeriveScaleDelta(const PolyQ31& scale, ScaleDeltaQ15* delta) {
  fw_derive_scale_delta(&scale, delta);
}
inline int16_t DeriveQ15(const CoeffQ31& coeff) { return fw_derive_q15(&coeff); }
inline void DeriveScaleTemperatureQ15(ScaleTemperatureConstantsQ31* st) {
  fw_derive_scale_temperature_q15(st);
}
inline void ImuConstantsInit(ImuConstants* constants) { fw_imu_constants_init(constants); }
inline uint8_t ImuConstantsBlockLength(uint8_t block_id) {
  return fw_imu_constants_block_length(block_id);
}
inline ConstantsStatus ImuConstantsWriteBlock(ImuConstants* constants,
                                              uint8_t block_id,
                                              const int16_t* words,
                                              uint8_t count) {
  return ToCxx(fw_imu_constants_write_block(constants, block_id, words, count));
}
inline ConstantsStatus ImuConstantsReadBlock(const ImuConstants* constants,
                                             uint8_t block_id,
                                             int16_t* words,
                                             uint8_t capacity,
                                             uint8_t* count) {
  return ToCxx(fw_imu_constants_read_block(constants, block_id, words, capacity, count));
}

// ---- imu_compensator.h
inline void ImuCompensate(DspEngine* engine,
                          const ImuConstants& constants,
                          ImuCompensationMode mode,
                          const ImuRawFrame& raw,
                          ImuCompensatedFrame* out) {
  fw_imu_compensate(engine->c(), &constants, static_cast<FwImuMode>(mode), &raw, out);
}
inline DspConfig CompensatorDspConfig() { return DspConfig::FromC(fw_compensator_dsp_config()); }

// ---- ads_constants.h
inline constexpr int8_t kAltitudeExponent = FW_ALTITUDE_EXPONENT;
inline constexpr int8_t kAirspeedExponent = FW_AIRSPEED_EXPONENT;
inline constexpr uint8_t kAdsSurfaceXDegree = FW_ADS_SURFACE_X_DEGREE;
inline constexpr uint8_t kAdsSurfaceYDegree = FW_ADS_SURFACE_Y_DEGREE;
inline constexpr uint8_t kSurfaceTerms = FW_SURFACE_TERMS;
using GainQ15 = FwGainQ15;
using HysteresisTermQ = FwHysteresisTermQ;
using SurfaceQ31 = FwSurfaceQ31;
using AdsConstants = FwAdsConstants;
enum AdsBlockId : uint8_t {
  kAdsBlockAltitude = FW_ADS_BLOCK_ALTITUDE,
  kAdsBlockAirspeed = FW_ADS_BLOCK_AIRSPEED,
};
inline constexpr uint8_t kGainWords = FW_GAIN_WORDS;
inline constexpr uint8_t kAdsHysteresisWords = FW_ADS_HYSTERESIS_WORDS;
inline constexpr uint8_t kAdsSurfaceBlockWords = FW_ADS_SURFACE_BLOCK_WORDS;
inline constexpr uint8_t kAdsMaxBlockWords = FW_ADS_MAX_BLOCK_WORDS;
inline int8_t AdsSurfaceExponent(uint8_t law, int8_t out_exponent) {
  return fw_ads_surface_exponent(law, out_exponent);
}
inline void AdsConstantsInit(AdsConstants* constants) { fw_ads_constants_init(constants); }
inline uint8_t AdsConstantsBlockLength(uint8_t block_id) {
  return fw_ads_constants_block_length(block_id);
}
inline ConstantsStatus AdsConstantsWriteBlock(AdsConstants* constants,
                                              uint8_t block_id,
                                              const int16_t* words,
                                              uint8_t count) {
  return ToCxx(fw_ads_constants_write_block(constants, block_id, words, count));
}
inline ConstantsStatus AdsConstantsReadBlock(const AdsConstants* constants,
                                             uint8_t block_id,
                                             int16_t* words,
                                             uint8_t capacity,
                                             uint8_t* count) {
  return ToCxx(fw_ads_constants_read_block(constants, block_id, words, capacity, count));
}

// ---- ads_compensator.h
using AdsHysteresisState = FwAdsHysteresisState;
inline void AdsHysteresisReset(AdsHysteresisState* state) { fw_ads_hysteresis_reset(state); }
inline void AdsCompensate(DspEngine* engine,
                          const AdsConstants& constants,
                          AdsCompensationMode mode,
                          const AdsRawFrame& raw,
                          AdsHysteresisState* state,
                          AdsCompensatedFrame* out) {
  fw_ads_compensate(engine->c(), &constants, static_cast<FwAdsMode>(mode), &raw, state, out);
}

// ---- data_payloads.h
struct ImuDataPayload {
  ImuRawFrame raw;
  ImuCompensationMode mode;
  /// Carried unless mode is kRaw; all zero after decoding a raw-mode packet.
  ImuCompensatedFrame compensated;

  FwImuDataPayload ToC() const {
    return FwImuDataPayload{raw, static_cast<FwImuMode>(mode), compensated};
  }
};
struct AdsDataPayload {
  AdsRawFrame raw;
  AdsCompensationMode mode;
  /// Carried unless mode is kRaw; all zero after decoding a raw-mode packet.
  AdsCompensatedFrame compensated;

  FwAdsDataPayload ToC() const {
    return FwAdsDataPayload{raw, static_cast<FwAdsMode>(mode), compensated};
  }
};
inline uint8_t ImuPayloadBytes(ImuCompensationMode mode) {
  return fw_imu_payload_bytes(static_cast<FwImuMode>(mode));
}
inline uint8_t AdsPayloadBytes(AdsCompensationMode mode) {
  return fw_ads_payload_bytes(static_cast<FwAdsMode>(mode));
}
inline bool IsImuModeByte(uint8_t mode) { return fw_is_imu_mode_byte(mode); }
inline bool IsAdsModeByte(uint8_t mode) { return fw_is_ads_mode_byte(mode); }
inline uint8_t EncodeImuPayload(const ImuDataPayload& data, uint8_t* out, uint8_t capacity) {
  const FwImuDataPayload c = data.ToC();
  return fw_encode_imu_payload(&c, out, capacity);
}
inline uint8_t EncodeAdsPayload(const AdsDataPayload& data, uint8_t* out, uint8_t capacity) {
  const FwAdsDataPayload c = data.ToC();
  return fw_encode_ads_payload(&c, out, capacity);
}
inline bool DecodeImuPayload(const uint8_t* payload, uint8_t length, ImuDataPayload* data) {
  FwImuDataPayload c{};
  if (!fw_decode_imu_payload(payload, length, &c)) return false;
  *data = ImuDataPayload{c.raw, static_cast<ImuCompensationMode>(c.mode), c.compensated};
  return true;
}
inline bool DecodeAdsPayload(const uint8_t* payload, uint8_t length, AdsDataPayload* data) {
  FwAdsDataPayload c{};
  if (!fw_decode_ads_payload(payload, length, &c)) return false;
  *data = AdsDataPayload{c.raw, static_cast<AdsCompensationMode>(c.mode), c.compensated};
  return true;
}
inline uint16_t EncodeImuDataFrame(const ImuDataPayload& data,
                                   uint8_t sequence,
                                   uint8_t tag,
                                   uint8_t* out,
                                   uint16_t out_capacity) {
  const FwImuDataPayload c = data.ToC();
  return fw_encode_imu_data_frame(&c, sequence, tag, out, out_capacity);
}
inline uint16_t EncodeAdsDataFrame(const AdsDataPayload& data,
                                   uint8_t sequence,
                                   uint8_t tag,
                                   uint8_t* out,
                                   uint16_t out_capacity) {
  const FwAdsDataPayload c = data.ToC();
  return fw_encode_ads_data_frame(&c, sequence, tag, out, out_capacity);
}

// ---- packet_codec.h
using Frame = FwFrame;
inline bool IsKnownPacketType(uint8_t type) { return fw_is_known_packet_type(type); }
inline bool IsPayloadLengthValid(uint8_t type, uint8_t payload_length) {
  return fw_is_payload_length_valid(type, payload_length);
}
inline uint16_t EncodeFrame(uint8_t type,
                            uint8_t sequence,
                            uint8_t tag,
                            const uint8_t* payload,
                            uint8_t payload_length,
                            uint8_t* out,
                            uint16_t out_capacity) {
  return fw_encode_frame(type, sequence, tag, payload, payload_length, out, out_capacity);
}
enum class DecodeEvent : uint8_t {
  kNeedMoreBytes = FW_DECODE_NEED_MORE_BYTES,
  kFrame = FW_DECODE_FRAME,
  kBadCrc = FW_DECODE_BAD_CRC,
  kBadLength = FW_DECODE_BAD_LENGTH,
  kUnknownType = FW_DECODE_UNKNOWN_TYPE,
};
struct DecodeResult {
  uint16_t consumed_bytes;  ///< bytes taken from the offered chunk
  DecodeEvent event;
};
using DecoderCounters = FwDecoderCounters;

/// The streaming decoder (FwPacketDecoder).
class PacketDecoder {
 public:
  PacketDecoder() { fw_decoder_init(&c_); }
  DecodeResult Feed(const uint8_t* bytes, uint16_t count, Frame* frame) {
    const FwDecodeResult r = fw_decoder_feed(&c_, bytes, count, frame);
    return DecodeResult{r.consumed_bytes, static_cast<DecodeEvent>(r.event)};
  }
  const DecoderCounters& counters() const { return c_.counters; }
  void DiscardBuffer() { fw_decoder_discard_buffer(&c_); }

 private:
  FwPacketDecoder c_;
};

// ---- flash_store.h
inline constexpr uint16_t kFlashPageWords = FW_FLASH_PAGE_WORDS;
inline constexpr uint16_t kFlashImageMagic = FW_FLASH_IMAGE_MAGIC;
inline constexpr uint16_t kFlashImageOverheadWords = FW_FLASH_IMAGE_OVERHEAD_WORDS;
inline constexpr uint16_t kFlashMaxPayloadWords = FW_FLASH_MAX_PAYLOAD_WORDS;
enum class FlashStatus : uint8_t {
  kOk = FW_FLASH_OK,
  kErased = FW_FLASH_ERASED,
  kBadMagic = FW_FLASH_BAD_MAGIC,
  kWrongKind = FW_FLASH_WRONG_KIND,
  kBadLength = FW_FLASH_BAD_LENGTH,
  kBadCrc = FW_FLASH_BAD_CRC,
};
struct FlashImageInfo {
  FlashStatus status;
  uint16_t constants_version;  ///< 0 unless status is kOk
  uint16_t image_crc;          ///< stored CRC, 0 unless status is kOk
  uint16_t payload_words;      ///< 0 unless status is kOk
};

/// The emulated constants page (FwFlashStore).
class FlashStore {
 public:
  FlashStore() { fw_flash_erase(&c_); }
  FlashStatus Commit(UnitKind kind, const int16_t* payload, uint16_t count) {
    return static_cast<FlashStatus>(
        fw_flash_commit(&c_, static_cast<FwUnitKind>(kind), payload, count));
  }
  FlashImageInfo Inspect(UnitKind kind) const {
    const FwFlashImageInfo i = fw_flash_inspect(&c_, static_cast<FwUnitKind>(kind));
    return FlashImageInfo{
        static_cast<FlashStatus>(i.status), i.constants_version, i.image_crc, i.payload_words};
  }
  FlashStatus Load(UnitKind kind, int16_t* payload, uint16_t capacity, uint16_t* count) const {
    return static_cast<FlashStatus>(
        fw_flash_load(&c_, static_cast<FwUnitKind>(kind), payload, capacity, count));
  }
  void Erase() { fw_flash_erase(&c_); }
  void InjectBitFlip(uint16_t word_index, uint8_t bit) {
    fw_flash_inject_bit_flip(&c_, word_index, bit);
  }
  FwFlashStore* c() { return &c_; }

 private:
  FwFlashStore c_;
};

// ---- maintenance_handler.h
struct UnitIdentity {
  UnitKind kind;
  uint32_t serial_number;
  uint8_t firmware_major;
  uint8_t firmware_minor;
  uint8_t firmware_patch;
};
using HandlerCounters = FwHandlerCounters;
using PortResult = FwPortResult;

/// The unit's maintenance port (FwMaintenanceHandler).
class MaintenanceHandler {
 public:
  /// A unit that has just been powered on with `flash` as its non-volatile store (not owned; must
  /// outlive the handler).
  MaintenanceHandler(const UnitIdentity& identity, FlashStore* flash) {
    const FwUnitIdentity c{static_cast<FwUnitKind>(identity.kind),
                           identity.serial_number,
                           identity.firmware_major,
                           identity.firmware_minor,
                           identity.firmware_patch};
    fw_maintenance_init(&c_, &c, flash->c());
  }

  PortResult Receive(const uint8_t* bytes,
                     uint16_t count,
                     uint8_t* response,
                     uint16_t response_capacity) {
    return fw_maintenance_receive(&c_, bytes, count, response, response_capacity);
  }
  uint16_t HandleRequest(const Frame& frame, uint8_t* response, uint16_t response_capacity) {
    return fw_maintenance_handle_request(&c_, &frame, response, response_capacity);
  }
  void PowerCycle() { fw_maintenance_power_cycle(&c_); }
  uint8_t TakeDataSequence() { return fw_maintenance_take_data_sequence(&c_); }

  UnitKind kind() const { return static_cast<UnitKind>(c_.identity.kind); }
  ImuCompensationMode imu_mode() const { return static_cast<ImuCompensationMode>(c_.mode); }
  AdsCompensationMode ads_mode() const { return static_cast<AdsCompensationMode>(c_.mode); }
  uint8_t tag() const { return c_.tag; }
  bool constants_valid() const { return c_.constants_valid; }
  uint16_t constants_version() const { return c_.constants_version; }
  uint16_t constants_crc() const { return c_.constants_crc; }
  const ImuConstants& imu_constants() const { return c_.imu_constants; }
  const AdsConstants& ads_constants() const { return c_.ads_constants; }
  const HandlerCounters& counters() const { return c_.counters; }
  const DecoderCounters& decoder_counters() const { return c_.decoder.counters; }

  /// The C port, for the unit's sample functions (adahrs_fw.h).
  FwMaintenanceHandler* c() { return &c_; }

 private:
  FwMaintenanceHandler c_;
};

}  // namespace adahrs::firmware_model
