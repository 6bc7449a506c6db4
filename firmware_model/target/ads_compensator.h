// The ADS compensator as the dsPIC runs it: one raw frame of ADS1254 codes in, altitude and
// airspeed out as Q31 values, every operation an instruction of the DSP engine model
// (reference-method.md step 6, thesis section 2.9). Each output is the degree (3, 5) surface of
// ads_constants.h in x = normalised pressure code and y = normalised (linearised) bridge-voltage
// code, by nested Horner (the four b_k(y), then Horner in x), then one saturating SFTAC to the
// output format: altitude and airspeed themselves (FW_ADS_LAW_DIRECT), or ps / qc in Pa that
// air_data_law.h turns into the output. Input normalisation is exact (32-bit centring, a
// power-of-two shift). Hysteresis: each block's two Preisach operators (preisach_q15.h) advance
// on the surface's result and on the die temperature tau(y), and their weighted states are added
// before the law; their memory (FwAdsHysteresisState) is the caller's and must see every frame.
// Units: codes in; ft and kt (or Pa before the law) out, formats in compensated_frame.h.
// Stages, hysteresis and why 32-bit normalisation: docs/firmware-compensator.md ("Stages",
// "Normalisation", "Hysteresis compensation", "Bridge-code linearisation").
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
