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

/// One hysteresis state's compensation term (docs/firmware-compensator.md "Hysteresis
/// compensation"); zero gain and inv_span leave the surface static.
struct HysteresisTermQ {
  CoeffQ31 inv_span;  ///< per unit of the operator's input; 0 = the state never moves
  GainQ15 gain;       ///< the surface's result units per unit state
};

struct SurfaceQ31 {
  InputNormQ31 x_norm;  ///< pressure code normalisation
  InputNormQ31 y_norm;  ///< normalisation of the (linearised) bridge-voltage code
  int8_t outer_work_exponent;
  PolyQ31 b[kAdsSurfaceXDegree + 1];  ///< b_k(y), degree kAdsSurfaceYDegree
  HysteresisTermQ pressure;           ///< driven by the surface's result
  HysteresisTermQ thermal;            ///< driven by tau(y)
  /// t1, t2, t3 of tau(y) = t1 y + t2 y^2 + t3 y^3 (Q15): the die temperature's change from y's
  /// centre, in a power of two of degC the exporter chooses
  int16_t die_temp_q15[3];
  BridgeLinearisationQ y_linearisation;  ///< bridge code -> the surface's y code
  uint8_t law;                           ///< AdsSurfaceLaw: what follows the surface
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
inline constexpr uint8_t kAdsSurfaceBlockWords = 2 * kNormWords + 5 + kSurfaceTerms * kCoeffWords +
                                                 kAdsHysteresisWords + kBridgeLinearisationWords +
                                                 1;
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
ConstantsStatus AdsConstantsWriteBlock(AdsConstants* constants,
                                       uint8_t block_id,
                                       const int16_t* words,
                                       uint8_t count);

/// Writes block `block_id` into `words` (capacity `capacity`), its length into `*count`.
ConstantsStatus AdsConstantsReadBlock(const AdsConstants* constants,
                                      uint8_t block_id,
                                      int16_t* words,
                                      uint8_t capacity,
                                      uint8_t* count);

}  // namespace adahrs::firmware_model
