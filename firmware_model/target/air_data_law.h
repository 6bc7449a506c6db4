// The air-data laws as the dsPIC runs them after a pressure surface (ads_compensator.h): ISA
// pressure altitude from static pressure and calibrated airspeed from impact pressure, by linear
// interpolation in the ROM tables of air_data_tables.h, every operation charged to the DSP engine.
//
// Altitude: p (Pa, Q31 at FW_PRESSURE_EXPONENT); index = mantissa >> 21 (128 Pa steps), fraction =
//   the low 21 bits as Q31; h = T[i] + (T[i+1] - T[i]) * fraction, ft as Q31 at
//   FW_ALTITUDE_EXPONENT. Interpolation error <= h''(p) * (128 Pa)^2 / 8: 0.3 ft at 11.6 kPa
//   (50,000 ft), less below, 1.1 ft at 6.2 kPa (63,000 ft). p below 6,144 Pa (above ~63,500 ft) or
//   negative: the 6,144 Pa altitude, FW_FLAG_OUTPUT_SATURATED.
// Airspeed: CAS^2 is interpolated the same way (256 Pa steps), because CAS^2 is smooth in qc
//   where CAS (~ sqrt(qc) near zero) is not; then CAS = isqrt(CAS^2 * 2^14) with 7 fractional bits
//   (1/128 kt), kt as Q31 at FW_AIRSPEED_EXPONENT. qc <= 0: 0 kt. qc from the last valid entry on
//   (48,896 Pa, 510 kt): that entry's CAS, FW_FLAG_OUTPUT_SATURATED.
// Cost: a table read is 2 TBLRDL/TBLRDH pairs; the integer square root is 16 steps of
// compare-subtract-shift on a 32-bit radicand.
// Left out: supersonic CAS, the ISA layers above 20 km (beyond the 16-bit-ft output anyway).
#ifndef ADAHRS_FW_AIR_DATA_LAW_H
#define ADAHRS_FW_AIR_DATA_LAW_H

#include <stdint.h>

#include "dsp_engine.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Which law follows an ADS surface (the last word of its constants block).
#define FW_ADS_LAW_DIRECT 0u        ///< the surface gives the output itself (the reference method)
#define FW_ADS_LAW_ISA_ALTITUDE 1u  ///< the surface gives static pressure; ISA altitude follows
#define FW_ADS_LAW_CAS 2u           ///< the surface gives impact pressure; CAS follows

/// ISA pressure altitude (ft, Q31 at FW_ALTITUDE_EXPONENT) of static pressure `ps_q31`.
int32_t fw_isa_altitude_q31(FwDspEngine* engine, int32_t ps_q31, uint16_t* flags);

/// Calibrated airspeed (kt, Q31 at FW_AIRSPEED_EXPONENT) of impact pressure `qc_q31`.
int32_t fw_cas_q31(FwDspEngine* engine, int32_t qc_q31, uint16_t* flags);

/// Entry `index` of the ISA altitude table / of the CAS^2 table (air_data_tables.h).
int32_t fw_isa_altitude_entry(uint16_t index);
int32_t fw_cas_squared_entry(uint16_t index);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_AIR_DATA_LAW_H
