// The Preisach hysteresis operator as the dsPIC runs it: the fixed-point twin of the law
// sensor_sim/preisach_hysteresis.h gives the pressure bridges (shared/physics.md section 6 rows 4
// and 7), driven by what the unit itself sees, so that the compensator can subtract the branch a
// bridge is on (ads_compensator.h). On a branch from (u_b, s_b) moving in direction d, travel
// t = min(|u - u_b| |inv_span|, 1) and state = s_b - 2 d t^2 (3 - 2 t); reversals begin branches,
// minor loops close exactly, a fresh operator starts on the virgin curve at its first input, and
// the branch starts are a stack of FW_PREISACH_DEPTH entries (the smallest loop forgotten when
// full). inv_span's sign keeps the physical convention (-1 after a rise, +1 after a fall); zero
// holds the state at 0.
// Units: u a Q31 mantissa at `input_exponent` (Pa for the pressure state, the die temperature
// tau for the thermal state); travel, weight and state Q15.
// Memory rules, formats, resolution and cycles: docs/firmware-compensator.md ("Hysteresis
// compensation"); the law: docs/models/pressure-bridge.md.
// Not modelled, as in the law it follows: creep. The bridge's own state survives power cycles,
// which the fresh operator cannot know.
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
