// The ADS compensator as the dsPIC runs it: one raw frame of ADS1254 codes in, altitude and
// airspeed out as Q31 values, every operation an instruction of the DSP engine model
// (reference-method.md step 6, thesis section 2.9).
//
// Each output is the degree (3, 5) surface of ads_constants.h in x = normalised pressure
// code and y = normalised bridge-voltage (temperature) code, by nested Horner: the four b_k(y)
// first (Horner at their own working exponents), then Horner in x at the surface's working
// exponent, then one saturating SFTAC to the output format: altitude and airspeed themselves
// (FW_ADS_LAW_DIRECT), or static / impact pressure in Pa that the ISA altitude or CAS law of
// air_data_law.h then turns into the output. Input normalisation is exact (32-bit
// centring in the accumulator, a power-of-two shift), which the 24-bit codes need: a Q15 x would
// resolve only 3e-5 of the fit span, ~1.5 ft over a 50,000 ft span before any other error.
// Hysteresis (ads_constants.h): after the surface, each block's two Preisach operators
// (preisach_q15.h) advance, the pressure one on the surface's result and the thermal one on
// the die temperature tau(y) (a Q15 cubic of the normalised bridge-voltage code), and
// gain_P s_P + gain_T s_T (Q15 gains, one MPY each) is added to the result before the law. The
// operators' memory is the caller's (FwAdsHysteresisState, RAM); it must see every frame in order.
// Operators that saturate while clamping their travel are not reported: that clamp is the law.
// Not modelled: Mach, TAS, OAT calibration; the ADC driver.
#ifndef ADAHRS_FW_ADS_COMPENSATOR_H
#define ADAHRS_FW_ADS_COMPENSATOR_H

#include "ads_constants.h"
#include "compensated_frame.h"
#include "dsp_engine.h"
#include "preisach_q15.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The hysteresis operators' memory of one unit: pressure and thermal state per bridge.
typedef struct {
  FwPreisachQ15 static_pressure;
  FwPreisachQ15 static_thermal;
  FwPreisachQ15 pitot_pressure;
  FwPreisachQ15 pitot_thermal;
} FwAdsHysteresisState;

/// Fresh operators (power-on, or new constants).
void fw_ads_hysteresis_reset(FwAdsHysteresisState* state);

/// Compensates one ADS frame in `mode` with `constants`, advancing `state` (untouched in RAW);
/// charges every instruction to `engine`.
void fw_ads_compensate(FwDspEngine* engine,
                       const FwAdsConstants* constants,
                       FwAdsMode mode,
                       const FwAdsRawFrame* raw,
                       FwAdsHysteresisState* state,
                       FwAdsCompensatedFrame* out);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_ADS_COMPENSATOR_H
