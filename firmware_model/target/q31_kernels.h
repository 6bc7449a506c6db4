// Double-word (Q31) kernels built only from DSP-engine instructions, so that every cycle they cost
// is counted (physics.md 5.3). fw_mul_q31(a, b) splits each operand into a signed high and an
// unsigned low word and sums three partial products (2 ah bh by a fractional MPY, the mixed terms
// by MUL.SU shifted right 15; al bl dropped): within [-3, 0] LSB of floor(a b / 2^31), 15 cycles,
// saturating only (-1)*(-1) -> 0x7FFFFFFF. Horner at a working exponent E (fixed_coeff.h):
// y_k = y_{k+1} x + c_k with every c_k aligned to E by one SFTAC, 25 cycles a step. The engine
// must be in fractional mode with 1.31 saturation.
// Units: Q31 mantissas and exponents (value = m * 2^(e - 31)); cycles.
// Derivation and cycle breakdown: docs/firmware-compensator.md ("Stages", fw_mul_q31).
#ifndef ADAHRS_FW_Q31_KERNELS_H
#define ADAHRS_FW_Q31_KERNELS_H

#include <stdint.h>

#include "dsp_engine.h"
#include "fixed_coeff.h"

#ifdef __cplusplus
extern "C" {
#endif

/// acc = v (LAC high word, MOV low word to ACCxL): 2 cycles.
void fw_load_q31(FwDspEngine* engine, FwAcc acc, int32_t v);
/// Reads ACCxH:ACCxL as int32 (2 cycles); exact while the accumulator is within 1.31.
int32_t fw_read_q31(FwDspEngine* engine, FwAcc acc);
/// SFTAC by a shift held in a W register (-16..16): the MOV that loads it, then the SFTAC.
void fw_sftac_by(FwDspEngine* engine, FwAcc acc, int16_t shift);
/// Shifts acc by `shift` (positive right), using as many SFTACs (+-16 each) as needed, at least
/// one.
void fw_shift_acc(FwDspEngine* engine, FwAcc acc, int16_t shift);
/// acc = a*b in Q31 (see derivation above); uses the other accumulator as scratch.
void fw_mul_q31(FwDspEngine* engine, FwAcc acc, int32_t a_q31, int32_t b_q31);
/// x = (v - centre) * 2^(v_exponent - shift) in Q31, saturating (SA set) if |x| >= 1: 10-11
/// cycles.
int32_t fw_normalise_q31(FwDspEngine* engine,
                         int32_t v,
                         int8_t v_exponent,
                         const FwInputNormQ31* norm);
/// p(x) by Horner at poly->work_exponent; result (Q31 at that exponent) in `acc` and returned.
int32_t fw_horner_q31(
    FwDspEngine* engine, FwAcc acc, const FwPolyQ31* poly, uint8_t degree, int32_t x_q31);
/// floor(sqrt(radicand)) by 16 steps of the restoring method on 32-bit W pairs: 192 cycles. The
/// root of a radicand at 2^(2n) is at 2^n (CAS: kt^2 2^14 -> kt 2^7; the bridge code's
/// linearisation: r 2^28 -> sqrt(r) 2^14).
uint16_t fw_integer_sqrt(FwDspEngine* engine, uint32_t radicand);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_Q31_KERNELS_H
