#include "q31_kernels.h"

#include "q_math.h"

void fw_load_q31(FwDspEngine* engine, FwAcc acc, int32_t v) {
  fw_dsp_lac(engine, acc, fw_high_word(v), 0);
  fw_dsp_mov_to_acc_low(engine, acc, fw_low_word(v));
}

int32_t fw_read_q31(FwDspEngine* engine, FwAcc acc) {
  const int16_t high = fw_dsp_mov_from_acc_high(engine, acc);
  const uint16_t low = fw_dsp_mov_from_acc_low(engine, acc);
  return fw_join_words(high, low);
}

void fw_shift_acc(FwDspEngine* engine, FwAcc acc, int16_t shift) {
  int16_t remaining = shift;
  do {
    const int16_t step = (remaining > 16) ? 16 : ((remaining < -16) ? -16 : remaining);
    fw_dsp_sftac(engine, acc, (int8_t)step);
    remaining = (int16_t)(remaining - step);
  } while (remaining != 0);
}

void fw_sftac_by(FwDspEngine* engine, FwAcc acc, int16_t shift) {
  fw_dsp_charge_mov(engine, 1u);  // the shift count into a W register
  fw_dsp_sftac(engine, acc, (int8_t)shift);
}

void fw_mul_q31(FwDspEngine* engine, FwAcc acc, int32_t a_q31, int32_t b_q31) {
  const FwAcc scratch = fw_other_acc(acc);
  fw_dsp_charge_mov(engine, 4u);  // ah, al, bh, bl into W registers
  const int16_t ah = fw_high_word(a_q31);
  const uint16_t al = fw_low_word(a_q31);
  const int16_t bh = fw_high_word(b_q31);
  const uint16_t bl = fw_low_word(b_q31);
  const int32_t ah_bl = fw_dsp_mul_su(engine, ah, bl);
  const int32_t bh_al = fw_dsp_mul_su(engine, bh, al);
  fw_load_q31(engine, scratch, ah_bl);
  fw_dsp_sftac(engine, scratch, 15);
  fw_load_q31(engine, acc, bh_al);
  fw_dsp_sftac(engine, acc, 15);
  fw_dsp_add_acc(engine, acc);
  fw_dsp_mpy(engine, scratch, ah, bh);
  fw_dsp_add_acc(engine, acc);
}

int32_t fw_normalise_q31(FwDspEngine* engine,
                         int32_t v,
                         int8_t v_exponent,
                         const FwInputNormQ31* norm) {
  fw_load_q31(engine, FW_ACC_A, v);
  fw_load_q31(engine, FW_ACC_B, norm->centre);
  fw_dsp_sub_acc(engine, FW_ACC_A);
  fw_dsp_charge_mov(engine, 1u);  // the shift count into a W register
  fw_shift_acc(engine, FW_ACC_A, (int16_t)((int16_t)norm->shift - (int16_t)v_exponent));
  return fw_read_q31(engine, FW_ACC_A);
}

int32_t fw_horner_q31(
    FwDspEngine* engine, FwAcc acc, const FwPolyQ31* poly, uint8_t degree, int32_t x_q31) {
  const FwAcc scratch = fw_other_acc(acc);
  fw_dsp_charge_mov(engine, 2u);  // coefficient pointer and loop count
  fw_load_q31(engine, acc, poly->coeff[degree].mantissa_q31);
  fw_dsp_charge_alu(engine, 1u);  // shift = work exponent - coefficient exponent
  fw_sftac_by(
      engine, acc, (int16_t)((int16_t)poly->work_exponent - (int16_t)poly->coeff[degree].exponent));
  int32_t y = fw_read_q31(engine, acc);
  for (int16_t k = (int16_t)((int16_t)degree - 1); k >= 0; --k) {
    fw_mul_q31(engine, acc, y, x_q31);
    fw_load_q31(engine, scratch, poly->coeff[k].mantissa_q31);
    fw_dsp_charge_alu(engine, 1u);  // shift = work exponent - coefficient exponent
    fw_sftac_by(engine,
                scratch,
                (int16_t)((int16_t)poly->work_exponent - (int16_t)poly->coeff[k].exponent));
    fw_dsp_add_acc(engine, acc);
    y = fw_read_q31(engine, acc);
    fw_dsp_charge_alu(engine, 1u);  // DEC loop count
    fw_dsp_charge_branch(engine, 1u);
  }
  return y;
}

uint16_t fw_integer_sqrt(FwDspEngine* engine, uint32_t radicand) {
  uint32_t remainder = radicand;
  uint32_t root = 0u;
  uint32_t bit = UINT32_C(1) << 30;
  for (uint8_t step = 0u; step < 16u; ++step) {
    fw_dsp_charge_alu(engine, 6u);  // trial = root + bit (2), compare (2), subtract (2)
    fw_dsp_charge_branch(engine, 1u);
    const uint32_t trial = root + bit;
    root >>= 1;
    if (remainder >= trial) {
      remainder -= trial;
      root += bit;
    }
    fw_dsp_charge_alu(engine, 4u);  // root >>= 1, bit >>= 2 on 32-bit pairs
    bit >>= 2;
  }
  return (uint16_t)root;
}
