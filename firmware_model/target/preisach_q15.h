// The Preisach hysteresis operator as the dsPIC runs it: the fixed-point twin of the law
// sensor_sim/preisach_hysteresis.h gives the pressure bridges (shared/physics.md section 6 rows 4
// and 7), driven by what the unit itself sees, so that the compensator can subtract the branch a
// bridge is on (ads_compensator.h).
//
//   on a branch that began at u_b with state s_b, moving in direction d = +-1 of the physical
//   quantity, travel t = min(|u - u_b| * |inv_span|, 1),
//   state = s_b - 2 d w,   w = t^2 (3 - 2 t)
//
// with the law's memory rules: a reversal begins a branch; passing back beyond the start of the
// previous branch closes the minor loop (exactly: the state there is the older branch's) and the
// state continues the older branch. That is what keeps the unit's own ADC noise (a reversal every
// few frames on a slow ramp) from holding the state back. A fresh operator (power-on) is in the
// virgin state at its first input u0: state 0, and moving away from u0 follows the virgin curve
// state = -d w(2 |u - u0| |inv_span|), which the oldest branch rejoins at its mirror point
// 2 u0 - u_b. The branch starts are a stack of FW_PREISACH_DEPTH entries in RAM; when it is full
// the smallest minor loop below the current branch is forgotten (noise makes small loops; a major
// branch's start is far from its neighbours and stays).
// The input u is a Q31 mantissa at `input_exponent` (fixed_coeff.h): the surface's pressure for
// the pressure state, the die temperature tau (ads_constants.h) for the thermal state.
// `inv_span` is the reciprocal of the travel to the full state in the input's units; its sign
// says which way the physical quantity moves when the input rises (negative for an input that
// falls as the quantity rises), so that the state keeps the physical convention: -1 after a rise,
// +1 after a fall. A zero inv_span holds the state at 0 (the term is off).
// Number formats: travel and the smoothstep weight w are Q15 in [0, 1] (w saturates at 0x7FFF);
// the state is Q15 in [-1, 1), saturated by the store. The Q15 state resolves 3e-5 of a half loop:
// 0.003 Pa of a 100 Pa loop. Cycle cost: about 10 on the first frame and on an unchanged input, 75
// on average otherwise (one MulQ31 for the travel, two MPYs for the weight, the state's add, the
// stack's bookkeeping), 109 at most measured with the stack full (preisach_q15_test.cc). Not
// modelled, as in the law it follows: creep. The bridge's own state survives power cycles, which
// the fresh operator cannot know.
#ifndef ADAHRS_FW_PREISACH_Q15_H
#define ADAHRS_FW_PREISACH_Q15_H

#include <stdint.h>

#include "dsp_engine.h"
#include "fixed_coeff.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FW_PREISACH_DEPTH 8u

/// The start of one branch.
typedef struct {
  int32_t input;
  int16_t state_q15;
} FwBranchStartQ15;

/// One operator's memory (RAM; zero-initialised is the fresh operator).
typedef struct {
  FwBranchStartQ15 branches[FW_PREISACH_DEPTH];  ///< oldest first
  uint8_t depth;                                 ///< 0: on the virgin curve
  int32_t origin_input;                          ///< the first input: the virgin curve's centre
  int32_t last_input;
  int16_t state_q15;
  int8_t direction;  ///< of the physical quantity on the current branch: +1, -1, 0 before any move
  uint8_t started;
} FwPreisachQ15;

/// Returns the operator to its fresh state (virgin, state 0, no input seen).
void fw_preisach_reset_q15(FwPreisachQ15* op);

/// Advances `op` to `input` (Q31 mantissa at `input_exponent`) and returns the state, Q15.
/// The caller guarantees inv_span->mantissa_q31 != INT32_MIN and
/// -31 <= input_exponent + inv_span->exponent <= 31 (ads_constants.c validates both).
int16_t fw_preisach_update_q15(FwDspEngine* engine,
                               FwPreisachQ15* op,
                               int32_t input,
                               int8_t input_exponent,
                               const FwCoeffQ31* inv_span);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_PREISACH_Q15_H
