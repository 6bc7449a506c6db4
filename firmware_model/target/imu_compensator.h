// The IM3 compensator as the dsPIC runs it: one raw frame in, nine Q31 values out, every operation
// an instruction of the DSP engine model so the frame's cycle cost is counted. Stages
// (reference-method.md steps 2-5; formats in imu_constants.h, outputs in compensated_frame.h):
// 1. duty U = T1/T2 - 0.5 by two DIV.UD (a 16-bit DIVF would miss the 0.1 mg budget 8x); gyro
// U = counts << 8. 2. thermal T = U - xi(tau), xi a cubic by Horner (format 2 Q31 x Q31, format 3
// Q31 x Q15). 3. sensor: accel (T - O)(1/S) in g (Eq. 12), gyro Eq. 23 cubic in deg/s; format 3
// times the scale factor F(tau_s) = 1 + delta. 4. full: pair mean Ca_axis (format 3: + q Ca^2),
// A = CA Ca (Eq. 26), G = CG Cg (Eq. 29; format 3: + GS A); slots 6..8 the pair half-difference.
// The engine is put in fractional mode with 1.31 saturation and convergent rounding at entry
// (one CORCON write). Saturation anywhere sets a flag in the frame; values are never wrapped.
// Units and frames: duty, counts, g, m/s^2 and deg/s in the body frame.
// Each stage's arithmetic and cycles: docs/firmware-compensator.md ("Stages", "Cycle table").
// Not modelled: the capture ISR that produces t1/t2, the gyro ADC driver, and run-time bias
// estimation (the unit's adaptive filter).
#ifndef ADAHRS_FW_IMU_COMPENSATOR_H
#define ADAHRS_FW_IMU_COMPENSATOR_H

#include "compensated_frame.h"
#include "dsp_engine.h"
#include "imu_constants.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Compensates one IMU frame in `mode` with `constants`; charges every instruction to `engine`.
void fw_imu_compensate(FwDspEngine* engine,
                       const FwImuConstants* constants,
                       FwImuMode mode,
                       const FwImuRawFrame* raw,
                       FwImuCompensatedFrame* out);

/// The DSP configuration the compensators run in (fractional, 1.31 saturation on A and B,
/// SATDW on, convergent rounding).
FwDspConfig fw_compensator_dsp_config(void);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_IMU_COMPENSATOR_H
