// The ADS unit's calibration constants in target (fixed-point) form and their block-wise access
// over the maintenance port (issue 3; reference-method.md step 6, thesis section 2.9).
//
// Each output is a bivariate polynomial surface of degree 3 in x and kAdsSurfaceYDegree (5) in y,
//   z = sum_{k=0..3} b_k(y) x^k,   b_k(y) = sum_{n=0..5} c_kn y^n,
// in normalised pressure counts x and normalised temperature (bridge-voltage) counts y, the
// latter linearised first when the block says so ("Linearisation" below):
//   altitude: x from the static-port code ps, y from the static bridge-voltage code
//   airspeed: x from the pitot (differential) code pt, y from the pitot bridge-voltage code
// The reference method's 10-term cubic (thesis section 2.9)
//   z = a + b x + c y + d x^2 + e y^2 + f x y + g x^3 + h y^3 + i x y^2 + j x^2 y
// is the instance b0 = a + c y + e y^2 + h y^3, b1 = b + f y + i y^2, b2 = d + j y, b3 = g with
// every other c_kn zero; degree 5 in y is what the bridge's ratiometric span tempco needs over
// -40...+85 degC (docs/calibration-strategies.md).
// Inputs are 24-bit ADS1254 codes held in int32 (raw integers, exponent 31), normalised as
// x = (code - centre) * 2^-shift, shift <= 31 (fixed_coeff.h).
// Evaluation is nested Horner, first each b_k(y) (all four of degree 5: constant time), then
//   z = ((b3 x + b2) x + b1) x + b0
// Each b_k is a PolyQ31 with its own working exponent; the outer Horner runs at the surface's
// working exponent (>= every b_k's) and its result is brought to the output exponent with
// saturation: altitude in ft at kAltitudeExponent (|alt| < 65,536 ft), airspeed in kt at
// kAirspeedExponent (|cas| < 512 kt).
//
// A law may follow the surface (air_data_law.h): with kAdsLawDirect the surface gives altitude
// (ft) or airspeed (kt) itself, as the reference method does; with kAdsLawIsaAltitude (altitude
// block only) it gives static pressure and with kAdsLawCas (airspeed block only) impact pressure,
// both in Pa at kPressureExponent, and the ISA or CAS law turns it into the output.
//
// Blocks:
//   0x21 altitude surface, 0x22 airspeed surface, 103 words each:
//     [InputNormQ31 x][InputNormQ31 y][outer work exponent][b0..b3 work exponents]
//     [CoeffQ31 c_00 .. c_05][c_10 .. c_15][c_20 .. c_25][c_30 .. c_35]   (b0 .. b3, y^0 first)
//     [pressure: CoeffQ31 inv_span][GainQ15 gain]                         (hysteresis, below)
//     [thermal:  int16 t1 t2 t3][CoeffQ31 inv_span][GainQ15 gain]
//     [linearisation: InputNormQ31 raw][int16 k]                          (below)
//     [law]                                                               (AdsSurfaceLaw)
// Linearisation (issue 6; bridge_linearisation.h): with k != 0 the surface's y is not the
// bridge-voltage code itself but its linearised code s, linear in the die temperature; y_norm
// then normalises s. k = 0 is the code itself (the reference's and the static strategies'
// surfaces). Blocks of 99 words (before the linearisation) are refused as kWrongLength.
// Hysteresis (issue 6; preisach_q15.h): the bridge's output carries its branch, a multiple of
// the states s_P (last pressure extreme) and s_T (last die-temperature extreme). The unit runs one
// operator per state and adds gain_P(tau) s_P + gain_T(tau) s_T to the surface's result z, before
// the law, each gain linear in the die temperature tau (below): a loop that is a fixed fraction of
// the bridge's output at one temperature follows the span tempco in pressure (+-15 %):
//   pressure operator: driven by z itself (Pa under a law), inv_span per unit of z;
//   thermal operator: driven by tau = t1 y + t2 y^2 + t3 y^3 (Q15), the die temperature's change
//     from the y-normalisation's centre in units of a power of two of degC chosen by the exporter,
//     y the surface's normalised bridge-voltage code in Q15 (the bridge's resistance is not
//     linear in temperature: its slope changes by about 40 % over -40...+85 degC, so a span in
//     code would be wrong by as much near the ends); inv_span per unit of tau (tau held as a Q31
//     mantissa at exponent 0).
// GainQ15: gain(tau) = (at_centre + per_tau tau) 2^(exponent - 15), evaluated in Q15 with
// saturation (the exporter keeps |at_centre| + |per_tau| within Q15); its exponent lies within
// 0..16 below the surface's result exponent. Each operator's input exponent plus its inv_span
// exponent must lie in -31..31; an inv_span mantissa of INT32_MIN is refused (its magnitude has no
// Q31 form); sum |t_k| must stay within Q15 (no Horner partial sum of tau overflows for |y| <= 1).
// Zero gains, inv_spans and t_k are the static surface.
// A write validates the whole block first and changes nothing unless it returns kOk. Overflow
// rule: each b_k must satisfy the PolyQ31 bound; the outer Horner must satisfy
// sum_k 2^(E_k) <= 2^E_outer (with |b_k| < 2^E_k this bounds every partial sum for |x| <= 1).
// A law the block does not allow is kOutOfRange.
// Not modelled: Mach and TAS (need OAT; computed downstream), OAT calibration.
#pragma once

#include <cstdint>

#include "firmware_model/target/air_data_law.h"
#include "firmware_model/target/bridge_linearisation.h"
#include "firmware_model/target/fixed_coeff.h"

namespace adahrs::firmware_model {

inline constexpr int8_t kAltitudeExponent = 16;  ///< altitude in ft, |alt| < 65,536 ft
inline constexpr int8_t kAirspeedExponent = 9;   ///< airspeed in kt, |cas| < 512 kt
inline constexpr uint8_t kAdsSurfaceXDegree = 3;
inline constexpr uint8_t kAdsSurfaceYDegree = 5;
inline constexpr uint8_t kSurfaceTerms = (kAdsSurfaceXDegree + 1) * (kAdsSurfaceYDegree + 1);
static_assert(kAdsSurfaceYDegree <= kMaxPolyDegree);

/// A gain linear in the die temperature tau (Q15): (at_centre + per_tau tau) 2^(exponent - 15).
struct GainQ15 {
  int16_t at_centre_q15;
  int16_t per_tau_q15;
  int8_t exponent;
};

/// One hysteresis state's compensation term (see "Hysteresis" above).
struct HysteresisTermQ {
  CoeffQ31 inv_span;  ///< per unit of the operator's input; 0 = the state never moves
  GainQ15 gain;       ///< the surface's result units per unit state
};

struct SurfaceQ31 {
  InputNormQ31 x_norm;      ///< pressure code normalisation
  InputNormQ31 y_norm;      ///< normalisation of the (linearised) bridge-voltage code
  int8_t outer_work_exponent;
  PolyQ31 b[kAdsSurfaceXDegree + 1];  ///< b_k(y), degree kAdsSurfaceYDegree
  HysteresisTermQ pressure;  ///< driven by the surface's result
  HysteresisTermQ thermal;   ///< driven by tau(y)
  int16_t die_temp_q15[3];   ///< t1, t2, t3 of tau(y)
  BridgeLinearisationQ y_linearisation;  ///< bridge code -> the surface's y code
  uint8_t law;              ///< AdsSurfaceLaw: what follows the surface
};

struct AdsConstants {
  SurfaceQ31 altitude;  ///< ft
  SurfaceQ31 airspeed;  ///< kt
};

enum AdsBlockId : uint8_t {
  kAdsBlockAltitude = 0x21,
  kAdsBlockAirspeed = 0x22,
};

inline constexpr uint8_t kGainWords = 3;
inline constexpr uint8_t kAdsHysteresisWords = 2 * (kCoeffWords + kGainWords) + 3;
inline constexpr uint8_t kAdsSurfaceBlockWords =
    2 * kNormWords + 5 + kSurfaceTerms * kCoeffWords + kAdsHysteresisWords +
    kBridgeLinearisationWords + 1;
inline constexpr uint8_t kAdsMaxBlockWords = kAdsSurfaceBlockWords;

/// The exponent a surface's result must reach: the output's (`out_exponent`) when `law` is
/// direct, the pressure's (kPressureExponent) under a law.
int8_t AdsSurfaceExponent(uint8_t law, int8_t out_exponent);

/// Uncalibrated state: all-zero direct surfaces (outputs read zero), centres 0, shifts 23, no
/// hysteresis terms, no linearisation.
void AdsConstantsInit(AdsConstants* constants);

/// Words in block `block_id`, or 0 if the block is unknown.
uint8_t AdsConstantsBlockLength(uint8_t block_id);

/// Replaces block `block_id` from `count` words; on any status but kOk nothing changes.
ConstantsStatus AdsConstantsWriteBlock(AdsConstants* constants, uint8_t block_id,
                                       const int16_t* words, uint8_t count);

/// Writes block `block_id` into `words` (capacity `capacity`), its length into `*count`.
ConstantsStatus AdsConstantsReadBlock(const AdsConstants* constants, uint8_t block_id,
                                      int16_t* words, uint8_t capacity, uint8_t* count);

}  // namespace adahrs::firmware_model
