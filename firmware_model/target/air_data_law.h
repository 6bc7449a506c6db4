// The air-data laws as the dsPIC runs them after a pressure surface (ads_compensator.h): ISA
// pressure altitude from static pressure and calibrated airspeed from impact pressure, by linear
// interpolation in the ROM tables of air_data_tables.h, every operation charged to the DSP engine.
// Altitude interpolates in 128 Pa steps (error <= 0.3 ft at 50,000 ft); below 6,144 Pa the output
// saturates. Airspeed interpolates CAS^2 in 256 Pa steps (smooth in qc where CAS is not), then
// CAS = isqrt(CAS^2 * 2^14) to 1/128 kt; qc <= 0 gives 0 kt, qc beyond 48,896 Pa (510 kt)
// saturates. Saturation sets FW_FLAG_OUTPUT_SATURATED.
// Units: p and qc in Pa as Q31 at FW_PRESSURE_EXPONENT; ft at FW_ALTITUDE_EXPONENT, kt at
// FW_AIRSPEED_EXPONENT.
// Indexing, error bounds and cost: docs/firmware-compensator.md ("Stages", the ADS laws).
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
