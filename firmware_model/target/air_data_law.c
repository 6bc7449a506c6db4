#include "air_data_law.h"

#include "air_data_tables.h"
#include "compensated_frame.h"
#include "q31_kernels.h"
#include "q_math.h"
#include "rom.h"

int32_t fw_isa_altitude_entry(uint16_t index) {
  return fw_rom_read_i32(&fw_isa_altitude_table_q31[index]);
}

int32_t fw_cas_squared_entry(uint16_t index) {
  return fw_rom_read_i32(&fw_cas_squared_table_q31[index]);
}

// T[i] + (T[i+1] - T[i]) * fraction, fraction = the low `step_log2` bits of `mantissa` as Q31.
static int32_t Interpolate(
    FwDspEngine* engine, const int32_t* table, uint16_t i, int32_t mantissa, uint8_t step_log2) {
  fw_dsp_charge_mov(engine, 4u);  // two table entries, TBLRDL + TBLRDH each
  fw_dsp_charge_alu(engine, 2u);  // 32-bit difference (SUB, SUBB)
  const int32_t low = fw_rom_read_i32(&table[i]);
  const int32_t difference = fw_rom_read_i32(&table[i + 1u]) - low;
  fw_dsp_charge_alu(engine, 3u);  // mask the low bits, shift them to Q31
  const uint32_t mask = (UINT32_C(1) << step_log2) - 1u;
  const int32_t fraction =
      fw_s32_from_bits(((uint32_t)mantissa & mask) << (uint8_t)(31u - step_log2));
  fw_mul_q31(engine, FW_ACC_A, difference, fraction);
  fw_load_q31(engine, FW_ACC_B, low);
  fw_dsp_add_acc(engine, FW_ACC_A);
  return fw_read_q31(engine, FW_ACC_A);
}

int32_t fw_isa_altitude_q31(FwDspEngine* engine, int32_t ps_q31, uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  fw_dsp_charge_alu(engine, 3u);  // index = mantissa >> 21, compare with the first valid entry
  fw_dsp_charge_branch(engine, 1u);
  const uint16_t index = (ps_q31 < 0) ? 0u : (uint16_t)((uint32_t)ps_q31 >> FW_ISA_TABLE_STEP_LOG2);
  if (index < FW_ISA_FIRST_VALID_ENTRY) {
    *flags |= FW_FLAG_OUTPUT_SATURATED;
    fw_dsp_charge_mov(engine, 2u);
    return fw_isa_altitude_entry(FW_ISA_FIRST_VALID_ENTRY);
  }
  return Interpolate(engine, fw_isa_altitude_table_q31, index, ps_q31, FW_ISA_TABLE_STEP_LOG2);
}

int32_t fw_cas_q31(FwDspEngine* engine, int32_t qc_q31, uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  fw_dsp_charge_alu(engine, 3u);
  fw_dsp_charge_branch(engine, 2u);
  if (qc_q31 <= 0) {
    return 0;
  }
  const uint16_t index = (uint16_t)((uint32_t)qc_q31 >> FW_CAS_TABLE_STEP_LOG2);
  int32_t cas_squared_q31 = 0;
  if (index >= FW_CAS_LAST_VALID_ENTRY) {
    *flags |= FW_FLAG_OUTPUT_SATURATED;
    fw_dsp_charge_mov(engine, 2u);
    cas_squared_q31 = fw_cas_squared_entry(FW_CAS_LAST_VALID_ENTRY);
  } else {
    cas_squared_q31 =
        Interpolate(engine, fw_cas_squared_table_q31, index, qc_q31, FW_CAS_TABLE_STEP_LOG2);
  }
  // fw_mul_q31 rounds down by up to 3 LSB: just above qc = 0 the interpolation can give -3.
  fw_dsp_charge_alu(engine, 1u);
  if (cas_squared_q31 < 0) {
    cas_squared_q31 = 0;
  }
  // Mantissa kt^2 * 2^12 < 2^30 (CAS < 512 kt): times 4 is kt^2 * 2^14, whose root is kt * 2^7.
  fw_dsp_charge_alu(engine, 2u);
  const uint16_t cas_q7 = fw_integer_sqrt(engine, (uint32_t)cas_squared_q31 << 2);
  fw_dsp_charge_alu(engine, 2u);  // to Q31 at FW_AIRSPEED_EXPONENT: kt * 2^22
  return fw_s32_from_bits((uint32_t)cas_q7 << 15);
}
