// The ADS compensator as the dsPIC runs it: one raw frame of ADS1254 codes in, altitude and
// airspeed out as Q31 values, every operation an instruction of the DSP engine model (issue 3;
// reference-method.md step 6, thesis section 2.9).
//
// Each output is the degree (3, 5) surface of ads_constants.h in x = normalised pressure
// code and y = normalised bridge-voltage (temperature) code, by nested Horner: the four b_k(y)
// first (Horner at their own working exponents), then Horner in x at the surface's working
// exponent, then one saturating SFTAC to the output format: altitude and airspeed themselves
// (kAdsLawDirect), or static / impact pressure in Pa that the ISA altitude or CAS law of
// air_data_law.h then turns into the output. Input normalisation is exact (32-bit
// centring in the accumulator, a power-of-two shift), which the 24-bit codes need: a Q15 x would
// resolve only 3e-5 of the fit span, ~1.5 ft over a 50,000 ft span before any other error.
// Not modelled: Mach, TAS, OAT calibration, hysteresis; the ADC driver.
#pragma once

#include "firmware_model/target/ads_constants.h"
#include "firmware_model/target/compensated_frame.h"
#include "firmware_model/target/dsp_engine.h"

namespace adahrs::firmware_model {

/// Compensates one ADS frame in `mode` with `constants`; charges every instruction to `engine`.
void AdsCompensate(DspEngine* engine, const AdsConstants& constants, AdsCompensationMode mode,
                   const AdsRawFrame& raw, AdsCompensatedFrame* out);

}  // namespace adahrs::firmware_model
