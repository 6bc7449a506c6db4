// One ADXL210E dual-axis ±10 g accelerometer chip with duty-cycle outputs, read by a dsPIC's
// input capture once per firmware frame (physics.md §1). Per axis: cross-axis input, one-pole
// output filter with exact Ornstein-Uhlenbeck noise through it, zero-g and sensitivity polynomials
// in ΔT = T − 25 °C, supply sensitivity, nonlinearity k2·a², duty clipped to [0, 1]; for the chip
// the T2 period (RSET, oscillator tolerance, tempco, jitter) and T1 = D·T2, captured on the timer
// grid by duty_cycle_modulator.h. Each term has its Adxl210eEffects switch.
// Frame: the chip package frame C (docs/frames-and-units.md): x_C, y_C sensitive, z_C the normal.
// Inputs: specific force in g (1 g = 9.80665 m/s²), die temperature in °C, supply in V, held
// constant over each frame; outputs T1, T2 in timer ticks (_cnt).
// Equations, sampling, noise, parameters and sources: docs/models/adxl210e.md.
// Left out: package alignment (im3_geometry.h rotates f_B into C), resonance and clipping beyond
// ±FS, self-test, turn-on transient, vibration inside a frame, supply dependence of T2 and
// sensitivity, thermal lag (the caller supplies the die temperature), timer-clock error.
#pragma once

#include <cstdint>
#include <span>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "common/random.h"
#include "sensor_sim/double_pair.h"
#include "sensor_sim/duty_cycle_modulator.h"

namespace adahrs::sensor_sim {

struct Adxl210eInput {
  double f_x_g;       ///< specific force along the chip's X sensitive axis (x_C), g
  double f_y_g;       ///< along the chip's Y sensitive axis (y_C), g
  double f_z_g;       ///< along the package normal (z_C); reaches the output only via cross-axis
  double die_temp_c;  ///< die temperature, °C
  double supply_v;    ///< supply voltage, V (nominal 5 V)
};

/// dsPIC input-capture differences for one duty-cycle period, timer ticks modulo 2^16.
struct Adxl210eCapture {
  uint16_t t1_cnt;  ///< rising to falling edge
  uint16_t t2_cnt;  ///< rising to next rising edge
};

struct Adxl210eOutput {
  Adxl210eCapture x;
  Adxl210eCapture y;
};

/// Separately switchable physical terms.
struct Adxl210eEffects {
  bool noise = true;                 ///< white noise density through the filter pole
  bool zero_g_tempco = true;         ///< zero-g duty vs die temperature (up to 3rd order)
  bool sensitivity_tempco = true;    ///< sensitivity vs die temperature (up to 3rd order)
  bool nonlinearity = true;          ///< quadratic term giving the BFSL nonlinearity
  bool cross_axis = true;            ///< transverse sensitivity and X-Y non-orthogonality
  bool supply_sensitivity = true;    ///< zero-g duty vs supply voltage
  bool t2_tempco = true;             ///< oscillator period vs die temperature
  bool t2_jitter = true;             ///< period-to-period jitter of T2
  bool capture_quantization = true;  ///< edges floored to the tick grid (off: interval rounded)
  bool filter = true;                ///< the XFILT/YFILT one-pole low-pass on the signal

  /// What the reference calibration assumes: offset tempco and cross-axis (it compensates them),
  /// noise, filter and capture quantisation (always present in a real reading); off: sensitivity
  /// tempco, nonlinearity, supply, T2 tempco and jitter.
  static Adxl210eEffects Nominal();
  /// Every term on (the truth model).
  static Adxl210eEffects All() { return {}; }
  bool operator==(const Adxl210eEffects&) const = default;
};

/// One sensitive axis' parameters. "Other" is the chip's other in-plane axis (Y for X, X for Y).
struct Adxl210eAxisParams {
  double zero_g_duty_ratio = 0.5;            ///< D0 at 25 °C and 5 V
  double sensitivity_pct_per_g = 4.0;        ///< S at 25 °C, duty % per g
  double zero_g_tc1_mg_per_c = 0.0;          ///< b1, as acceleration at S_25
  double zero_g_tc2_mg_per_c2 = 0.0;         ///< b2
  double zero_g_tc3_mg_per_c3 = 0.0;         ///< b3
  double sensitivity_tc1_ppm_per_c = 0.0;    ///< s1
  double sensitivity_tc2_ppm_per_c2 = 0.0;   ///< s2
  double sensitivity_tc3_ppm_per_c3 = 0.0;   ///< s3
  double zero_g_supply_pct_per_v = 1.0;      ///< k_V, duty % per V
  double nonlinearity_pct_fs = 0.2;          ///< signed BFSL deviation over ±10 g, % of 10 g
  double cross_other_ratio = 0.0;            ///< c_io, output g per g along the other axis
  double cross_z_ratio = 0.0;                ///< c_iz, output g per g along z_C
  double noise_density_ug_per_rthz = 200.0;  ///< N, one-sided, µg/√Hz
  double filter_r_ohm = 32e3;                ///< on-chip filter resistor
  double filter_c_f = 0.1e-6;                ///< external filter capacitor
  bool operator==(const Adxl210eAxisParams&) const = default;
};

struct Adxl210eParams {
  Adxl210eAxisParams x;
  Adxl210eAxisParams y;
  double xy_nonorthogonality_deg = 0.0;    ///< δ_xy: y_C tilted towards x_C
  double rset_ohm = 125e3;                 ///< RSET, sets T2 = RSET/125 MΩ
  double t2_oscillator_error_ratio = 0.0;  ///< δ_osc: oscillator tolerance for a given RSET
  double t2_tc_ppm_per_c = 0.0;            ///< α
  double t2_jitter_ppm = 20.0;             ///< rms error of one period, ppm of T2
  double timer_clock_hz = 29.4912e6;       ///< capture timer tick rate (Fcy / prescaler)
  Adxl210eEffects effects;

  /// The datasheet typical part: every signed term at 0, D0 50 %, S 4 %/g, supply 1 %/V,
  /// nonlinearity 0.2 % FS, 200 µg/√Hz, 32 kΩ, 0.1 µF, RSET 125 kΩ, Fcy 29.4912 MHz.
  static Adxl210eParams Typical();
  /// One chip drawn from the datasheet distributions (docs/models/adxl210e.md), fixed per seed.
  static Adxl210eParams Draw(uint64_t seed);
  nlohmann::json ToJson() const;
  static Adxl210eParams FromJson(const common::ParamReader& reader);
  bool operator==(const Adxl210eParams&) const = default;
};

class Adxl210e {
 public:
  /// `noise_seed` fixes noise, jitter and the initial DCM phase; `frame_period_s` is the firmware
  /// frame (0.01 at 100 Hz). Throws std::invalid_argument when T2 does not fit twice in a frame
  /// with 25 % margin, or does not fit the 16-bit timer with the same margin.
  Adxl210e(const Adxl210eParams& params, uint64_t noise_seed, double frame_period_s);

  /// Advances one frame with `input` held over it and returns both axes' captures.
  Adxl210eOutput Step(const Adxl210eInput& input);

  /// Step of every chip in `chips` with its own input, bit for bit as calling Step on each in
  /// turn. Faster: each stage of the step (draws and DCM period; filter and noise; duty and
  /// captures) runs for all chips before the next, so the chips' independent dependency chains sit
  /// side by side in the instruction stream and the processor overlaps them.
  /// Precondition: the three spans have the same size.
  static void StepEach(std::span<Adxl210e> chips,
                       std::span<const Adxl210eInput> inputs,
                       std::span<Adxl210eOutput> outputs);

 private:
  // What one frame's step carries from one stage to the next.
  struct Frame {
    DcmPeriod period;
    DoublePair z;       // the filter noise's standard normals
    DoublePair a_in_g;  // input after the cross-axis matrix
    DoublePair a_g;     // filtered, noisy acceleration at the sample instant
    double dtemp_c;
    double dsupply_v;
  };
  inline Frame BeginFrame(const Adxl210eInput& input);
  inline Adxl210eOutput FinishFrame(const Frame& frame) const;
  // Both axes' constants (precomputed) and filter state, lane 0 the X axis and lane 1 the Y axis:
  // the two axes share every instruction of the step (double_pair.h).
  struct Axes {
    DoublePair frame_decay;        // exp(−Δ/τ)
    DoublePair exponent_per_tick;  // −t_tick/τ: e^{−s/τ} = exp(s_cnt · exponent_per_tick)
    DoublePair noise_rms_g;        // N/√(4τ), stationary rms of the filtered noise
    DoublePair zero_g_duty_ratio;
    DoublePair sensitivity_ratio_per_g;
    DoublePair zero_g_tc_ratio[3];  // D0 change per °C^k, duty ratio
    DoublePair sensitivity_tc[3];   // relative S change per °C^k
    DoublePair supply_ratio_per_v;
    DoublePair quadratic_per_g;    // k2
    DoublePair cross_other_ratio;  // c_xy on X; c_yx + sin(δ_xy) on Y (0 with cross_axis off)
    DoublePair cross_z_ratio;      // c_xz, c_yz (0 with cross_axis off)
    DoublePair filter_g = {};      // a_f signal at the frame start
    DoublePair noise_g = {};       // noise at the previous sample instant
    DoublePair decay_to_frame_end = {};  // exp(−(Δ − s_prev)/τ)
  };
  static Axes MakeAxes(const Adxl210eParams& params, double frame_period_s);
  inline DoublePair FilteredAccel(DoublePair a_in_g, double sample_cnt, DoublePair z);
  inline DoublePair Duty(DoublePair a_g, double dtemp_c, double dsupply_v) const;

  Adxl210eEffects effects_;
  Axes axes_;
  double t2_25_cnt_;
  double t2_tc_per_c_;
  double t2_jitter_ratio_;
  DutyCycleModulator dcm_;
  common::Rng noise_rng_;
  common::Rng jitter_rng_;
  bool started_ = false;
};

}  // namespace adahrs::sensor_sim
