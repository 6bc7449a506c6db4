// The last-extreme hysteresis operator as the dsPIC runs it (issue 6): the fixed-point twin of the
// law sensor_sim/last_extreme_hysteresis.h gives the pressure bridges (shared/physics.md section 6
// rows 4 and 7), driven by what the unit itself sees, so that the compensator can subtract the
// branch a bridge is on (ads_compensator.h).
//
//   after a reversal at u_ext with state s_ext, moving in direction d = +-1 of the physical
//   quantity, travel t = min(|u - u_ext| * |inv_span|, 1),
//   state = s_ext + w (-d - s_ext),   w = t^2 (3 - 2 t)
//
// The input u is a Q31 mantissa at `input_exponent` (fixed_coeff.h): the surface's pressure for
// the pressure state, the raw bridge-voltage code (exponent 31) for the thermal state.
// `inv_span` is the reciprocal of the travel to the full state in the input's units; its sign
// says which way the physical quantity moves when the input rises (negative for a code that falls
// as the die warms), so that the state keeps the physical convention: -1 after a rise, +1 after a
// fall. A zero inv_span holds the state where it is (the term is off).
// Number formats: travel and the smoothstep weight w are Q15 in [0, 1] (w saturates at 0x7FFF);
// the state is Q15 in [-1, 1). The Q15 state resolves 3e-5 of a half loop: 0.003 Pa of a 100 Pa
// loop. Cycle cost: 10 on the first frame and on an unchanged input, about 40 otherwise
// (one MulQ31 for the travel, two MPYs for the weight and the state).
// Not modelled, as in the law it follows: older extremes (Preisach memory), creep. A fresh
// operator (power-on) starts at state 0 and learns the branch from the first reversal on; the
// bridge's own state survives power cycles, which the operator cannot know.
#pragma once

#include <cstdint>

#include "firmware_model/target/dsp_engine.h"
#include "firmware_model/target/fixed_coeff.h"

namespace adahrs::firmware_model {

/// One operator's memory (RAM; zero-initialised is the fresh operator).
struct LastExtremeQ15 {
  int32_t last_input;
  int32_t extreme_input;
  int16_t extreme_state_q15;
  int16_t state_q15;
  int8_t direction;  ///< of the physical quantity at the last move: +1, -1, 0 before any move
  uint8_t started;
};

/// Returns the operator to its fresh state (state 0, no input seen).
void LastExtremeResetQ15(LastExtremeQ15* op);

/// Advances `op` to `input` (Q31 mantissa at `input_exponent`) and returns the state, Q15.
/// The caller guarantees inv_span.mantissa_q31 != INT32_MIN and
/// -31 <= input_exponent + inv_span.exponent <= 31 (ads_constants.cc validates both).
int16_t LastExtremeUpdateQ15(DspEngine* engine, LastExtremeQ15* op, int32_t input,
                             int8_t input_exponent, const CoeffQ31& inv_span);

}  // namespace adahrs::firmware_model
