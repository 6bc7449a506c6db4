// The ADS unit's calibration constants in target (fixed-point) form and their block-wise access
// over the maintenance port (reference-method.md step 6, thesis section 2.9).
// Per output a surface z = sum_{k=0..3} b_k(y) x^k, b_k(y) = sum_{n=0..5} c_kn y^n, in the
// normalised pressure code x (altitude: the static code ps; airspeed: the pitot code pt) and the
// same bridge's normalised bridge-voltage code y, linearised first if the block says so
// (bridge_linearisation.h); then the bridge's hysteresis terms (preisach_q15.h) and a law
// (air_data_law.h): altitude in ft or airspeed in kt directly, or static / impact pressure in Pa
// turned into them by the ISA / CAS law. Inputs: 24-bit ADS1254 codes held in int32. A refused
// write changes nothing. Block layouts, exponents and what a write checks:
// docs/firmware-compensator.md ("Constants blocks", "Hysteresis compensation", "Bridge-code
// linearisation").
// Not modelled: Mach and TAS (need OAT; computed downstream), OAT calibration.
#ifndef ADAHRS_FW_ADS_CONSTANTS_H
#define ADAHRS_FW_ADS_CONSTANTS_H

#include <stdint.h>

#include "air_data_law.h"
#include "bridge_linearisation.h"
#include "fixed_coeff.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FW_ALTITUDE_EXPONENT 16  ///< altitude in ft, |alt| < 65,536 ft
#define FW_AIRSPEED_EXPONENT 9   ///< airspeed in kt, |cas| < 512 kt
#define FW_ADS_SURFACE_X_DEGREE 3u
#define FW_ADS_SURFACE_Y_DEGREE 5u  ///< at most FW_MAX_POLY_DEGREE
#define FW_SURFACE_TERMS ((FW_ADS_SURFACE_X_DEGREE + 1u) * (FW_ADS_SURFACE_Y_DEGREE + 1u))

/// A gain linear in the die temperature tau (Q15): (at_centre + per_tau tau) 2^(exponent - 15).
typedef struct {
  int16_t at_centre_q15;
  int16_t per_tau_q15;
  int8_t exponent;
} FwGainQ15;

/// One hysteresis state's compensation term (docs/firmware-compensator.md "Hysteresis
/// compensation"); zero gain and inv_span leave the surface static.
typedef struct {
  FwCoeffQ31 inv_span;  ///< per unit of the operator's input; 0 = the state never moves
  FwGainQ15 gain;       ///< the surface's result units per unit state
} FwHysteresisTermQ;

typedef struct {
  FwInputNormQ31 x_norm;  ///< pressure code normalisation
  FwInputNormQ31 y_norm;  ///< normalisation of the (linearised) bridge-voltage code
  int8_t outer_work_exponent;
  FwPolyQ31 b[FW_ADS_SURFACE_X_DEGREE + 1u];  ///< b_k(y), degree FW_ADS_SURFACE_Y_DEGREE
  FwHysteresisTermQ pressure;                 ///< driven by the surface's result
  FwHysteresisTermQ thermal;                  ///< driven by tau(y)
  /// t1, t2, t3 of tau(y) = t1 y + t2 y^2 + t3 y^3 (Q15): the die temperature's change from y's
  /// centre, in a power of two of degC the exporter chooses
  int16_t die_temp_q15[3];
  FwBridgeLinearisationQ y_linearisation;  ///< bridge code -> the surface's y code
  uint8_t law;                             ///< FW_ADS_LAW_*: what follows the surface
} FwSurfaceQ31;

typedef struct {
  FwSurfaceQ31 altitude;  ///< ft
  FwSurfaceQ31 airspeed;  ///< kt
} FwAdsConstants;

#define FW_ADS_BLOCK_ALTITUDE 0x21u
#define FW_ADS_BLOCK_AIRSPEED 0x22u

#define FW_GAIN_WORDS 3u
#define FW_ADS_HYSTERESIS_WORDS ((2u * (FW_COEFF_WORDS + FW_GAIN_WORDS)) + 3u)
#define FW_ADS_SURFACE_BLOCK_WORDS                                                             \
  ((2u * FW_NORM_WORDS) + 5u + (FW_SURFACE_TERMS * FW_COEFF_WORDS) + FW_ADS_HYSTERESIS_WORDS + \
   FW_BRIDGE_LINEARISATION_WORDS + 1u)
#define FW_ADS_MAX_BLOCK_WORDS FW_ADS_SURFACE_BLOCK_WORDS

/// The exponent a surface's result must reach: the output's (`out_exponent`) when `law` is
/// direct, the pressure's (FW_PRESSURE_EXPONENT) under a law.
int8_t fw_ads_surface_exponent(uint8_t law, int8_t out_exponent);

/// Uncalibrated state: all-zero direct surfaces (outputs read zero), centres 0, shifts 23, no
/// hysteresis terms, no linearisation.
void fw_ads_constants_init(FwAdsConstants* constants);

/// Words in block `block_id`, or 0 if the block is unknown.
uint8_t fw_ads_constants_block_length(uint8_t block_id);

/// Replaces block `block_id` from `count` words; on any status but OK nothing changes.
FwConstantsStatus fw_ads_constants_write_block(FwAdsConstants* constants,
                                               uint8_t block_id,
                                               const int16_t* words,
                                               uint8_t count);

/// Writes block `block_id` into `words` (capacity `capacity`), its length into `*count`.
FwConstantsStatus fw_ads_constants_read_block(const FwAdsConstants* constants,
                                              uint8_t block_id,
                                              int16_t* words,
                                              uint8_t capacity,
                                              uint8_t* count);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_ADS_CONSTANTS_H
