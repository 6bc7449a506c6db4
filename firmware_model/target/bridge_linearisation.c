#include "bridge_linearisation.h"

#include "compensated_frame.h"
#include "q31_kernels.h"
#include "q_math.h"

// Codes are the ADS1254's 24 bits: an origin and a half-width within 2^24 keep s inside int32.
#define MAX_CODE_LOG2 24u

int32_t fw_linearised_bridge_code(FwDspEngine* engine,
                                  const FwBridgeLinearisationQ* linearisation,
                                  int32_t y_code,
                                  uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  fw_dsp_charge_alu(engine, 1u);  // k == 0?
  fw_dsp_charge_branch(engine, 1u);
  if (linearisation->curvature_q13 == 0) {
    return y_code;
  }
  const int16_t v_q15 =
      fw_high_word(fw_normalise_q31(engine, y_code, 31, &linearisation->raw_norm));
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
  const int32_t kv_q28 = fw_dsp_mul_ss(engine, linearisation->curvature_q13, v_q15);
  fw_dsp_charge_alu(engine, 2u);                              // + 2^28 on the W pair (ADD, ADDC)
  const int32_t radicand_q28 = INT32_C(0x10000000) + kv_q28;  // 1 + k v in Q28
  fw_dsp_charge_branch(engine, 1u);                           // r < 0?
  if (radicand_q28 < 0) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
  const uint16_t root_q14 =
      fw_integer_sqrt(engine, (radicand_q28 < 0) ? 0u : (uint32_t)radicand_q28);
  fw_dsp_charge_alu(engine, 2u);  // (1 + root) 2^13: LSR, ADD
  const uint16_t half_root_q13 = (uint16_t)(root_q14 >> 1);
  const int16_t divisor_q13 = (int16_t)(INT32_C(0x2000) + (int32_t)half_root_q13);
  fw_dsp_charge_alu(engine, 3u);  // v 2^28 into a W pair: sign-extend, two shifts
  const FwDivResult quotient_q15 =
      fw_dsp_div_sd(engine, (int32_t)v_q15 * (INT32_C(1) << 13), divisor_q13);
  fw_dsp_charge_alu(engine, 6u);  // q 2^(shift - 14) on a W pair (4), + origin (ADD, ADDC)
  const int64_t offset = fw_shift_arith((int64_t)quotient_q15.quotient,
                                        (int8_t)(14 - (int16_t)linearisation->raw_norm.shift));
  return (int32_t)((int64_t)linearisation->raw_norm.centre + offset);
}

FwConstantsStatus fw_bridge_linearisation_from_words(const int16_t* words,
                                                     FwBridgeLinearisationQ* out) {
  FwBridgeLinearisationQ decoded;
  const FwConstantsStatus s = fw_norm_from_words(words, MAX_CODE_LOG2, &decoded.raw_norm);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  decoded.curvature_q13 = words[FW_NORM_WORDS];
  const int32_t centre = decoded.raw_norm.centre;
  const int32_t code_limit = INT32_C(1) << MAX_CODE_LOG2;
  if ((centre >= code_limit) || (centre <= -code_limit)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  *out = decoded;
  return FW_CONSTANTS_OK;
}

void fw_bridge_linearisation_to_words(const FwBridgeLinearisationQ* linearisation, int16_t* words) {
  fw_norm_to_words(&linearisation->raw_norm, words);
  words[FW_NORM_WORDS] = linearisation->curvature_q13;
}
