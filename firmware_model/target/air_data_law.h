// The air-data laws as the dsPIC runs them after a pressure surface (ads_compensator.h): ISA
// pressure altitude from static pressure and calibrated airspeed from impact pressure, by linear
// interpolation in the ROM tables of air_data_tables.h, every operation charged to the DSP engine.
//
// Altitude: p (Pa, Q31 at kPressureExponent); index = mantissa >> 21 (128 Pa steps), fraction =
//   the low 21 bits as Q31; h = T[i] + (T[i+1] - T[i]) * fraction, ft as Q31 at kAltitudeExponent.
//   Interpolation error <= h''(p) * (128 Pa)^2 / 8: 0.3 ft at 11.6 kPa (50,000 ft), less below,
//   1.1 ft at 6.2 kPa (63,000 ft). p below 6,144 Pa (above ~63,500 ft) or negative: the 6,144 Pa
//   altitude, kFlagOutputSaturated.
// Airspeed: CAS^2 is interpolated the same way (256 Pa steps), because CAS^2 is smooth in qc
//   where CAS (~ sqrt(qc) near zero) is not; then CAS = isqrt(CAS^2 * 2^14) with 7 fractional bits
//   (1/128 kt), kt as Q31 at kAirspeedExponent. qc <= 0: 0 kt. qc from the last valid entry on
//   (48,896 Pa, 510 kt): that entry's CAS, kFlagOutputSaturated.
// Cost: a table read is 2 TBLRDL/TBLRDH pairs; the integer square root is 16 steps of
// compare-subtract-shift on a 32-bit radicand.
// Left out: supersonic CAS, the ISA layers above 20 km (beyond the 16-bit-ft output anyway).
#pragma once

#include <cstdint>

#include "firmware_model/target/dsp_engine.h"

namespace adahrs::firmware_model {

/// Which law follows an ADS surface (the last word of its constants block).
enum AdsSurfaceLaw : uint8_t {
  kAdsLawDirect = 0,       ///< the surface gives the output itself (the reference method)
  kAdsLawIsaAltitude = 1,  ///< the surface gives static pressure; ISA altitude follows
  kAdsLawCas = 2,          ///< the surface gives impact pressure; calibrated airspeed follows
};

/// ISA pressure altitude (ft, Q31 at kAltitudeExponent) of static pressure `ps_q31`.
int32_t IsaAltitudeQ31(DspEngine* engine, int32_t ps_q31, uint16_t* flags);

/// Calibrated airspeed (kt, Q31 at kAirspeedExponent) of impact pressure `qc_q31`.
int32_t CasQ31(DspEngine* engine, int32_t qc_q31, uint16_t* flags);

}  // namespace adahrs::firmware_model
