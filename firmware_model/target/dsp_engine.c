#include "dsp_engine.h"

#include "q_math.h"

const char* fw_dsp_op_name(FwDspOp op) {
  static const char* const kOpNames[FW_OP_COUNT] = {
      "MPY",     "MAC",     "MSC",        "LAC",     "SAC",      "SAC.R",       "SFTAC",  "ADD Acc",
      "SUB Acc", "NEG Acc", "ADD Ws,Acc", "CLR Acc", "MOV ACCx", "MUL.SS",      "MUL.SU", "MUL.UU",
      "DIVF",    "DIV.SD",  "DIV.UD",     "MOV",     "ALU",      "BRA (taken)", "CALL",   "RETURN",
  };
  return kOpNames[op];
}

FwDspConfig fw_dsp_config_default(void) {
  FwDspConfig config;
  config.integer_mode = false;
  config.unsigned_mode = false;
  config.saturate_a = true;
  config.saturate_b = true;
  config.super_saturation = false;
  config.saturate_writes = true;
  config.convergent_rounding = true;
  return config;
}

void fw_dsp_reset_counters(FwDspEngine* engine) {
  engine->cycles = 0u;
  engine->instructions = 0u;
  for (uint8_t i = 0u; i < (uint8_t)FW_OP_COUNT; ++i) {
    engine->op_counts[i] = 0u;
  }
}

void fw_dsp_init(FwDspEngine* engine, FwDspConfig config) {
  engine->config = config;
  engine->acc[FW_ACC_A] = 0;
  engine->acc[FW_ACC_B] = 0;
  engine->sa = false;
  engine->sb = false;
  engine->math_error = false;
  fw_dsp_reset_counters(engine);
}

bool fw_dsp_test_and_clear_saturation(FwDspEngine* engine) {
  fw_dsp_charge(engine, FW_OP_ALU, 2u);
  const bool any = engine->sa || engine->sb;
  engine->sa = false;
  engine->sb = false;
  return any;
}

bool fw_dsp_overflowed31(const FwDspEngine* engine, FwAcc acc) {
  return (engine->acc[acc] > FW_ACC31_MAX) || (engine->acc[acc] < FW_ACC31_MIN);
}

FwDivResult fw_dsp_div_f(FwDspEngine* engine, int16_t num, int16_t den) {
  fw_dsp_charge(engine, FW_OP_DIV_F, 1u);
  const int32_t abs_num = (num < 0) ? -(int32_t)num : (int32_t)num;
  const int32_t abs_den = (den < 0) ? -(int32_t)den : (int32_t)den;
  FwDivResult result;
  if ((den == 0) || (abs_num >= abs_den)) {
    engine->math_error = true;
    result.quotient = ((num < 0) != (den < 0)) ? (int32_t)FW_Q15_MIN : (int32_t)FW_Q15_MAX;
    result.remainder = 0;
  } else {
    // Quotient of (num * 2^15) / den truncated toward zero; remainder has the dividend's sign
    // (C99 6.5.5: integer division truncates toward zero).
    const int32_t dividend = (int32_t)num * INT32_C(32768);
    result.quotient = dividend / (int32_t)den;
    result.remainder = dividend % (int32_t)den;
  }
  return result;
}

FwDivResult fw_dsp_div_sd(FwDspEngine* engine, int32_t num, int16_t den) {
  fw_dsp_charge(engine, FW_OP_DIV_SD, 1u);
  FwDivResult result;
  result.remainder = 0;
  if (den == 0) {
    engine->math_error = true;
    result.quotient = (num < 0) ? (int32_t)INT16_MIN : (int32_t)INT16_MAX;
  } else {
    const int64_t q = (int64_t)num / (int64_t)den;
    if ((q > (int64_t)INT16_MAX) || (q < (int64_t)INT16_MIN)) {
      engine->math_error = true;
      result.quotient = (q < 0) ? (int32_t)INT16_MIN : (int32_t)INT16_MAX;
    } else {
      result.quotient = (int32_t)q;
      result.remainder = (int32_t)((int64_t)num % (int64_t)den);
    }
  }
  return result;
}

FwDivResult fw_dsp_div_ud(FwDspEngine* engine, uint32_t num, uint16_t den) {
  fw_dsp_charge(engine, FW_OP_DIV_UD, 1u);
  FwDivResult result;
  if ((den == 0u) || ((num / (uint32_t)den) > (uint32_t)UINT16_MAX)) {
    engine->math_error = true;
    result.quotient = (int32_t)UINT16_MAX;
    result.remainder = 0;
  } else {
    const uint32_t quotient = num / (uint32_t)den;  // <= UINT16_MAX
    const uint32_t remainder = num % (uint32_t)den;
    result.quotient = (int32_t)quotient;
    result.remainder = (int32_t)remainder;
  }
  return result;
}
