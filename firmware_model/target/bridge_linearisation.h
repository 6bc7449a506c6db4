// The bridge-voltage thermometer's linearisation: what the ADS firmware makes of a pressure
// bridge's voltage code y before the surface sees it (ads_constants.h).
//
// Under constant current the bridge voltage is nearly a quadratic of the die temperature
// (sensor_sim/pressure_bridge.h: R_B = R_B0 (1 + alpha dT + beta dT^2)), so the code's slope
// changes by a factor of 1.5 to 3 over -40...+85 degC. A polynomial in y then follows the
// temperature dependence of the bridge's offset and span badly where the slope is smallest (the
// cold end): on a unit with beta = 9.8 ppm/degC^2 the surface's residual was 21 Pa. Inverting the
// quadratic y = origin + b dT + (kappa b^2 / 4) dT^2 gives a code that is linear in dT:
//   s = origin + 2 (y - origin) / (1 + sqrt(1 + kappa (y - origin))) = origin + b dT,
// the rationalised form of origin + (2/kappa)(sqrt(1 + kappa (y - origin)) - 1): no division by
// kappa, so kappa -> 0 is the code itself without loss of precision.
//
// Fixed point, with v = (y - origin) 2^-shift (the raw normalisation, |v| < 1) and
// k = kappa 2^shift:
//   v       Q15, the normalised code's high word (|v| >= 1 sets FW_FLAG_INPUT_SATURATED);
//   k       Q13 (|k| < 4: a model-1230 bridge's quadratic tempco makes the radicand run from
//           about 0.27 to 2.2 over -40...+85 degC, kappa |y - origin| up to 1.2, and the
//           power-of-two half-width adds up to 2x);
//   r       1 + k v as r 2^28 (MUL.SS of k and v, plus 2^28), r < 5; a negative r (a code beyond
//           where the quadratic turns, outside any calibrated range) is taken as 0 and sets
//           FW_FLAG_INPUT_SATURATED;
//   root    sqrt(r) 2^14 by the restoring integer square root (q31_kernels.h);
//   q       v / (1 + root) in Q15: DIV.SD of v 2^28 by (1 + root) 2^13 (< 26,600), |q| <= 1;
//   s       origin + q 2^(shift - 14), an int32 code the surface's own normalisation takes.
// Resolution: s moves in steps of 2^(shift - 14) codes, about 1/16,000 of the code box's
// half-width (0.004 degC over -40...+85 degC); the root's truncation (2^-14) and the divisor's
// (2^-13) add at most 2^-12.4 of v. k = 0 returns y unchanged (the static strategies' surfaces,
// bit for bit).
// Cost: 245 cycles with k != 0 (the square root 192, DIV.SD 19), at most 8 with k = 0 (measured:
// tests/firmware_model/bridge_linearisation_test.cc).
// Left out: the cubic term of the current source's tempco and the bridge resistance's pressure
// dependence; what they leave is smooth in y and the surface's polynomial takes it up.
#ifndef ADAHRS_FW_BRIDGE_LINEARISATION_H
#define ADAHRS_FW_BRIDGE_LINEARISATION_H

#include <stdint.h>

#include "dsp_engine.h"
#include "fixed_coeff.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Words of a linearisation in a surface block: [FwInputNormQ31 raw][int16 k].
#define FW_BRIDGE_LINEARISATION_WORDS (FW_NORM_WORDS + 1u)

typedef struct {
  FwInputNormQ31 raw_norm;  ///< centre = the origin code, shift: v = (y - origin) 2^-shift
  int16_t curvature_q13;    ///< k = kappa 2^shift in Q13; 0: s = y
} FwBridgeLinearisationQ;

/// The linearised code s of bridge-voltage code `y_code`; sets FW_FLAG_INPUT_SATURATED in *flags
/// when |v| >= 1 or r < 0.
int32_t fw_linearised_bridge_code(FwDspEngine* engine,
                                  const FwBridgeLinearisationQ* linearisation,
                                  int32_t y_code,
                                  uint16_t* flags);

/// Block words <-> linearisation; a shift beyond 24 or an origin outside +-2^24 (the ADS1254's
/// codes: s then stays inside int32) is OUT_OF_RANGE.
FwConstantsStatus fw_bridge_linearisation_from_words(const int16_t* words,
                                                     FwBridgeLinearisationQ* out);
void fw_bridge_linearisation_to_words(const FwBridgeLinearisationQ* linearisation, int16_t* words);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_BRIDGE_LINEARISATION_H
