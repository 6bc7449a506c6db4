// The bridge-voltage thermometer's linearisation: what the ADS firmware makes of a pressure
// bridge's voltage code y before the surface sees it (ads_constants.h). Under constant current the
// bridge voltage is nearly a quadratic of the die temperature (sensor_sim/pressure_bridge.h:
// R_B = R_B0 (1 + alpha dT + beta dT^2)), so a polynomial in y follows the bridge's offset and span
// tempco badly at the cold end. Inverting y = origin + b dT + (kappa b^2 / 4) dT^2 gives a code
// linear in dT: s = origin + 2 (y - origin) / (1 + sqrt(1 + kappa (y - origin))) = origin + b dT.
// Fixed point: v = (y - origin) 2^-shift in Q15, k = kappa 2^shift in Q13, r = 1 + k v as r 2^28,
// sqrt(r) 2^14 by the integer square root (q31_kernels.h), q = v / (1 + root) by one DIV.SD, and
// s = origin + q 2^(shift - 14). A negative r or |v| >= 1 sets FW_FLAG_INPUT_SATURATED; k = 0
// returns y unchanged (the static strategies' surfaces, bit for bit).
// Units: ADS1254 codes in and out (int32).
// Derivation, formats, resolution, cost (245 cycles): docs/firmware-compensator.md ("Bridge-code
// linearisation").
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
