// The IM3 compensator as the dsPIC runs it: one raw frame in, nine Q31 values out, every operation
// an instruction of the DSP engine model so the frame's cycle cost is counted.
//
// Stages (reference-method.md steps 2-5; formats in imu_constants.h, outputs in
// compensated_frame.h):
//   1. Duty U = T1/T2 - 0.5 per accelerometer channel: two DIV.UD give floor(t1 2^32 / t2)
//      exactly (t1 << 16 / t2, then remainder << 16 / t2), then U_q31 = (r >> 1) - 2^30
//      = floor(U 2^31). A 16-bit DIVF alone resolves only 3e-5 duty (0.76 mg at 25 g/duty), 8x
//      the 0.1 mg budget, so the 32-bit quotient is needed (38 cycles per channel).
//      Gyro U = counts << 8 (exponent 23), saturating for |counts| >= 2^23.
//   2. Thermal (Eq. 4-5): tau = (t - centre) 2^-shift, xi(tau) by Horner (degree 3), T = U - xi;
//      format 2 in Q31 x Q31 steps, format 3 in Q31 x Q15 steps (tau rounded to Q15).
//   3. Sensor calibration: accel Ca = (T - O) (1/S) in g (Eq. 12); gyro Eq. 23 cubic in
//      x = (T - centre) 2^-shift, deg/s.
//      Format 3: each channel times its scale factor F(tau_s) = 1 + delta, tau_s the normalised
//      count of the temperature sensor its thermal block names, delta a MAC chain on tau_s's Q15
//      powers (imu_constants.h FwScaleDeltaQ15).
//   4. Full calibration: Ca_axis = (ch1 + ch2)/2 (pair mean), format 3: + q ca_axis^2;
//      A = CA Ca (Eq. 26) in m/s^2, G = CG Cg (Eq. 29), format 3: + GS A (q, GS, ca and A in
//      Q15 there); slots 6..8 carry the pair half-difference (ch1 - ch2)/2 in g.
// The engine is put in fractional mode with 1.31 saturation and convergent rounding at entry
// (one CORCON write). Saturation anywhere sets a flag in the frame; values are never wrapped.
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
