#include "sensor_sim/adxl210e.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/units.h"
#include "sensor_sim/fast_math.h"

namespace adahrs::sensor_sim {
namespace {

constexpr double kReferenceTemp_c = 25.0;
constexpr double kNominalSupply_v = 5.0;
constexpr double kFullScale_g = 10.0;                 // ±10 g range (physics.md §1.1, V)
constexpr double kT2PerRset_s_per_ohm = 1.0 / 125e6;  // T2 = RSET / 125 MΩ (physics.md §1.1, V)
constexpr double kRatioPerPct = 0.01;
constexpr double kRatioPerPpm = 1e-6;
constexpr double kGPerMg = 1e-3;
constexpr double kGPerUg = 1e-6;
// Headroom kept for T2 drift with temperature and jitter when checking that T2 fits.
constexpr double kT2Margin = 1.25;
// exp(−Δ/τ) must stay a normal double (e^−700 ≈ 1e−304); it is also the range of BoundedExp.
constexpr double kMaxFramePerTau = kBoundedExpMaxArg;

std::string Describe(const char* what, double value) {
  std::ostringstream s;
  s << what << " = " << value;
  return s.str();
}

nlohmann::json AxisToJson(const Adxl210eAxisParams& p) {
  return {{"zero_g_duty_ratio", p.zero_g_duty_ratio},
          {"sensitivity_pct_per_g", p.sensitivity_pct_per_g},
          {"zero_g_tc1_mg_per_c", p.zero_g_tc1_mg_per_c},
          {"zero_g_tc2_mg_per_c2", p.zero_g_tc2_mg_per_c2},
          {"zero_g_tc3_mg_per_c3", p.zero_g_tc3_mg_per_c3},
          {"sensitivity_tc1_ppm_per_c", p.sensitivity_tc1_ppm_per_c},
          {"sensitivity_tc2_ppm_per_c2", p.sensitivity_tc2_ppm_per_c2},
          {"sensitivity_tc3_ppm_per_c3", p.sensitivity_tc3_ppm_per_c3},
          {"zero_g_supply_pct_per_v", p.zero_g_supply_pct_per_v},
          {"nonlinearity_pct_fs", p.nonlinearity_pct_fs},
          {"cross_other_ratio", p.cross_other_ratio},
          {"cross_z_ratio", p.cross_z_ratio},
          {"noise_density_ug_per_rthz", p.noise_density_ug_per_rthz},
          {"filter_r_ohm", p.filter_r_ohm},
          {"filter_c_f", p.filter_c_f}};
}

// Allowed ranges are physical plausibility limits, several times the datasheet spreads
// (docs/models/adxl210e.md), not acceptance limits.
Adxl210eAxisParams AxisFromJson(const common::ParamReader& r) {
  Adxl210eAxisParams p;
  p.zero_g_duty_ratio = r.Number("zero_g_duty_ratio", 0.2, 0.8, "ratio");
  p.sensitivity_pct_per_g = r.Number("sensitivity_pct_per_g", 2.0, 6.0, "%/g");
  p.zero_g_tc1_mg_per_c = r.Number("zero_g_tc1_mg_per_c", -20.0, 20.0, "mg/degC");
  p.zero_g_tc2_mg_per_c2 = r.Number("zero_g_tc2_mg_per_c2", -0.5, 0.5, "mg/degC^2");
  p.zero_g_tc3_mg_per_c3 = r.Number("zero_g_tc3_mg_per_c3", -0.01, 0.01, "mg/degC^3");
  p.sensitivity_tc1_ppm_per_c = r.Number("sensitivity_tc1_ppm_per_c", -2000.0, 2000.0, "ppm/degC");
  p.sensitivity_tc2_ppm_per_c2 = r.Number("sensitivity_tc2_ppm_per_c2", -20.0, 20.0, "ppm/degC^2");
  p.sensitivity_tc3_ppm_per_c3 = r.Number("sensitivity_tc3_ppm_per_c3", -0.5, 0.5, "ppm/degC^3");
  p.zero_g_supply_pct_per_v = r.Number("zero_g_supply_pct_per_v", -10.0, 10.0, "%/V");
  p.nonlinearity_pct_fs = r.Number("nonlinearity_pct_fs", -2.0, 2.0, "% of 10 g");
  p.cross_other_ratio = r.Number("cross_other_ratio", -0.1, 0.1, "g/g");
  p.cross_z_ratio = r.Number("cross_z_ratio", -0.1, 0.1, "g/g");
  p.noise_density_ug_per_rthz = r.Number("noise_density_ug_per_rthz", 0.0, 2000.0, "ug/sqrt(Hz)");
  p.filter_r_ohm = r.Number("filter_r_ohm", 20e3, 45e3, "ohm");
  p.filter_c_f = r.Number("filter_c_f", 1e-9, 10e-6, "F");
  r.ExpectAllKeysUsed();
  return p;
}

}  // namespace

Adxl210eEffects Adxl210eEffects::Nominal() {
  Adxl210eEffects e;
  e.sensitivity_tempco = false;
  e.nonlinearity = false;
  e.supply_sensitivity = false;
  e.t2_tempco = false;
  e.t2_jitter = false;
  return e;
}

Adxl210eParams Adxl210eParams::Typical() { return Adxl210eParams{}; }

Adxl210eParams Adxl210eParams::Draw(uint64_t seed) {
  // Convention (docs/models/adxl210e.md): a datasheet min/max or "tolerance" is the 3σ bound of
  // Rng::Tolerance; a datasheet "typ" spread is one σ, so its tolerance argument is 3× the figure.
  common::Rng rng(seed);
  Adxl210eParams p;
  const double filter_r_lot_ohm = rng.Tolerance(32e3, 4.8e3);  // ±15 %, R
  auto draw_axis = [&](Adxl210eAxisParams& a) {
    a.zero_g_duty_ratio = rng.Tolerance(0.5, 0.08);                // ±2 g at 4 %/g, R
    a.sensitivity_pct_per_g = rng.Tolerance(4.0, 0.8);             // 3.2 … 4.8 %/g, R
    a.zero_g_tc1_mg_per_c = rng.Tolerance(0.0, 6.0);               // ±2 mg/°C typ, R
    a.zero_g_tc2_mg_per_c2 = rng.Tolerance(0.0, 0.015);            // E
    a.zero_g_tc3_mg_per_c3 = rng.Tolerance(0.0, 1.5e-4);           // E
    a.sensitivity_tc1_ppm_per_c = rng.Tolerance(0.0, 240.0);       // ±0.5 % over 60 °C typ, R
    a.sensitivity_tc2_ppm_per_c2 = rng.Tolerance(0.0, 0.9);        // E
    a.sensitivity_tc3_ppm_per_c3 = rng.Tolerance(0.0, 0.015);      // E
    a.zero_g_supply_pct_per_v = rng.Tolerance(1.0, 3.0);           // 1 %/V typ, 4 %/V max, R
    a.nonlinearity_pct_fs = rng.Tolerance(0.0, 0.6);               // 0.2 % FS typ, R
    a.cross_other_ratio = rng.Tolerance(0.0, 0.06);                // ±2 % typ, R
    a.cross_z_ratio = rng.Tolerance(0.0, 0.06);                    // ±2 % typ, R
    a.noise_density_ug_per_rthz = rng.Tolerance(200.0, 60.0);      // E spread about the V typ
    a.filter_r_ohm = filter_r_lot_ohm * rng.Tolerance(1.0, 0.01);  // on-die match ±1 %, E
    a.filter_c_f = rng.Tolerance(0.1e-6, 0.01e-6);                 // ±10 % capacitor, E
  };
  draw_axis(p.x);
  draw_axis(p.y);
  p.xy_nonorthogonality_deg = rng.Tolerance(0.0, 0.03);   // 0.01° typ, R
  p.rset_ohm = rng.Tolerance(125e3, 1.25e3);              // 1 % resistor, E
  p.t2_oscillator_error_ratio = rng.Tolerance(0.0, 0.3);  // ±30 %, R
  p.t2_tc_ppm_per_c = rng.Tolerance(0.0, 300.0);          // E
  p.t2_jitter_ppm = rng.Tolerance(20.0, 15.0);            // E
  return p;
}

nlohmann::json Adxl210eParams::ToJson() const {
  return {{"x", AxisToJson(x)},
          {"y", AxisToJson(y)},
          {"xy_nonorthogonality_deg", xy_nonorthogonality_deg},
          {"rset_ohm", rset_ohm},
          {"t2_oscillator_error_ratio", t2_oscillator_error_ratio},
          {"t2_tc_ppm_per_c", t2_tc_ppm_per_c},
          {"t2_jitter_ppm", t2_jitter_ppm},
          {"timer_clock_hz", timer_clock_hz},
          {"effects",
           {{"noise", effects.noise},
            {"zero_g_tempco", effects.zero_g_tempco},
            {"sensitivity_tempco", effects.sensitivity_tempco},
            {"nonlinearity", effects.nonlinearity},
            {"cross_axis", effects.cross_axis},
            {"supply_sensitivity", effects.supply_sensitivity},
            {"t2_tempco", effects.t2_tempco},
            {"t2_jitter", effects.t2_jitter},
            {"capture_quantization", effects.capture_quantization},
            {"filter", effects.filter}}}};
}

Adxl210eParams Adxl210eParams::FromJson(const common::ParamReader& reader) {
  Adxl210eParams p;
  p.x = AxisFromJson(reader.Child("x"));
  p.y = AxisFromJson(reader.Child("y"));
  p.xy_nonorthogonality_deg = reader.Number("xy_nonorthogonality_deg", -1.0, 1.0, "deg");
  // T2 adjustable 0.5 … 10 ms (physics.md §1.1, V) → RSET 62.5 kΩ … 1.25 MΩ.
  p.rset_ohm = reader.Number("rset_ohm", 62.5e3, 1.25e6, "ohm");
  p.t2_oscillator_error_ratio = reader.Number("t2_oscillator_error_ratio", -0.5, 0.5, "ratio");
  p.t2_tc_ppm_per_c = reader.Number("t2_tc_ppm_per_c", -2000.0, 2000.0, "ppm/degC");
  p.t2_jitter_ppm = reader.Number("t2_jitter_ppm", 0.0, 1000.0, "ppm");
  p.timer_clock_hz = reader.Number("timer_clock_hz", 1e5, 40e6, "Hz");  // dsPIC ≤ 40 MIPS
  const common::ParamReader e = reader.Child("effects");
  p.effects.noise = e.Flag("noise");
  p.effects.zero_g_tempco = e.Flag("zero_g_tempco");
  p.effects.sensitivity_tempco = e.Flag("sensitivity_tempco");
  p.effects.nonlinearity = e.Flag("nonlinearity");
  p.effects.cross_axis = e.Flag("cross_axis");
  p.effects.supply_sensitivity = e.Flag("supply_sensitivity");
  p.effects.t2_tempco = e.Flag("t2_tempco");
  p.effects.t2_jitter = e.Flag("t2_jitter");
  p.effects.capture_quantization = e.Flag("capture_quantization");
  p.effects.filter = e.Flag("filter");
  e.ExpectAllKeysUsed();
  reader.ExpectAllKeysUsed();
  return p;
}

Adxl210e::Axes Adxl210e::MakeAxes(const Adxl210eParams& params, double frame_period_s) {
  Axes a;
  for (int lane = 0; lane < 2; ++lane) {
    const Adxl210eAxisParams& p = lane == 0 ? params.x : params.y;
    const double tau_s = p.filter_r_ohm * p.filter_c_f;
    if (frame_period_s / tau_s > kMaxFramePerTau) {
      throw std::invalid_argument("Adxl210e: filter time constant too short for the frame (" +
                                  Describe("tau_s", tau_s) + ", " +
                                  Describe("frame_period_s", frame_period_s) + ")");
    }
    a.frame_decay[lane] = std::exp(-frame_period_s / tau_s);
    a.exponent_per_tick[lane] = -1.0 / (params.timer_clock_hz * tau_s);
    // One-sided density N through 1/(1 + sτ): σ² = ∫ N²/(1 + (2πfτ)²) df = N²/(4τ).
    a.noise_rms_g[lane] = p.noise_density_ug_per_rthz * kGPerUg / std::sqrt(4.0 * tau_s);
    a.zero_g_duty_ratio[lane] = p.zero_g_duty_ratio;
    a.sensitivity_ratio_per_g[lane] = p.sensitivity_pct_per_g * kRatioPerPct;
    const double mg_to_duty = a.sensitivity_ratio_per_g[lane] * kGPerMg;
    a.zero_g_tc_ratio[0][lane] = p.zero_g_tc1_mg_per_c * mg_to_duty;
    a.zero_g_tc_ratio[1][lane] = p.zero_g_tc2_mg_per_c2 * mg_to_duty;
    a.zero_g_tc_ratio[2][lane] = p.zero_g_tc3_mg_per_c3 * mg_to_duty;
    a.sensitivity_tc[0][lane] = p.sensitivity_tc1_ppm_per_c * kRatioPerPpm;
    a.sensitivity_tc[1][lane] = p.sensitivity_tc2_ppm_per_c2 * kRatioPerPpm;
    a.sensitivity_tc[2][lane] = p.sensitivity_tc3_ppm_per_c3 * kRatioPerPpm;
    a.supply_ratio_per_v[lane] = p.zero_g_supply_pct_per_v * kRatioPerPct;
    // k2·a² deviates from its least-squares line over [−FS, FS] by at most (2/3)·k2·FS² (at ±FS;
    // the line is the mean FS²/3), so k2 = 1.5·nonlinearity/FS makes that maximum nl·FS.
    a.quadratic_per_g[lane] = 1.5 * p.nonlinearity_pct_fs * kRatioPerPct / kFullScale_g;
  }
  const bool cross = params.effects.cross_axis;
  a.cross_other_ratio =
      cross ? DoublePair{params.x.cross_other_ratio,
                         params.y.cross_other_ratio +
                             std::sin(common::DegToRad(params.xy_nonorthogonality_deg))}
            : DoublePair{0.0, 0.0};
  a.cross_z_ratio =
      cross ? DoublePair{params.x.cross_z_ratio, params.y.cross_z_ratio} : DoublePair{0.0, 0.0};
  return a;
}

Adxl210e::Adxl210e(const Adxl210eParams& params, uint64_t noise_seed, double frame_period_s)
    : effects_(params.effects),
      axes_(MakeAxes(params, frame_period_s)),
      t2_25_cnt_(params.rset_ohm * kT2PerRset_s_per_ohm * (1.0 + params.t2_oscillator_error_ratio) *
                 params.timer_clock_hz),
      t2_tc_per_c_(params.effects.t2_tempco ? params.t2_tc_ppm_per_c * kRatioPerPpm : 0.0),
      t2_jitter_ratio_(params.effects.t2_jitter ? params.t2_jitter_ppm * kRatioPerPpm : 0.0),
      dcm_(0.0, 0.0, 0.0),
      noise_rng_(common::Rng::Derive(noise_seed, 0)),
      jitter_rng_(common::Rng::Derive(noise_seed, 1)) {
  if (!(frame_period_s > 0.0) || !std::isfinite(frame_period_s)) {
    throw std::invalid_argument("Adxl210e: " + Describe("frame_period_s", frame_period_s) +
                                " must be positive");
  }
  const double frame_cnt = frame_period_s * params.timer_clock_hz;
  if (kT2Margin * t2_25_cnt_ > frame_cnt / 2.0) {
    throw std::invalid_argument("Adxl210e: T2 must fit twice in a frame with 25 % margin (" +
                                Describe("t2_cnt", t2_25_cnt_) + ", " +
                                Describe("frame_cnt", frame_cnt) + ")");
  }
  if (kT2Margin * t2_25_cnt_ >= 65536.0) {
    throw std::invalid_argument("Adxl210e: T2 must fit the 16-bit timer with 25 % margin (" +
                                Describe("t2_cnt", t2_25_cnt_) + "); use a timer prescaler");
  }
  common::Rng phase_rng(common::Rng::Derive(noise_seed, 2));
  const double initial_end_cnt = -phase_rng.Uniform() * t2_25_cnt_;
  dcm_ = DutyCycleModulator(frame_cnt, initial_end_cnt, phase_rng.Uniform());
}

inline DoublePair Adxl210e::FilteredAccel(DoublePair a_in_g, double sample_cnt, DoublePair z) {
  if (!effects_.filter && !effects_.noise) return a_in_g;
  // Input u held over the frame; sample instant s after the frame start. Exact one-pole solution:
  //   y(s) = u + (y(0) − u)·e^{−s/τ},   y(Δ) = u + (y(s) − u)·e^{−(Δ−s)/τ}.
  // Noise between consecutive sample instants s' (previous frame) and s (this frame), gap
  // Δ − s' + s:  n ← φ·n + σ·√(1 − φ²)·z with φ = e^{−(Δ−s')/τ}·e^{−s/τ} (exact AR(1) step).
  // s = sample_cnt·t_tick, so s/τ = sample_cnt·t_tick/τ with t_tick/τ precomputed (a multiply
  // instead of a divide on the frame's critical path; the argument differs from −(s)/τ by a
  // rounding, ~1e-16 relative). 0 ≤ s ≤ Δ and Δ/τ ≤ kMaxFramePerTau = kBoundedExpMaxArg (checked
  // in MakeAxes), so the argument is inside BoundedExp's range, where it is within 1 ulp of
  // std::exp (fast_math.h).
  const DoublePair decay_to_sample = BoundedExpPair(sample_cnt * axes_.exponent_per_tick);
  const DoublePair decay_to_frame_end = axes_.frame_decay / decay_to_sample;
  DoublePair signal_g = a_in_g;
  if (effects_.filter) {
    signal_g = a_in_g + (axes_.filter_g - a_in_g) * decay_to_sample;
    axes_.filter_g = a_in_g + (signal_g - a_in_g) * decay_to_frame_end;
  }
  if (effects_.noise) {
    const DoublePair phi = axes_.decay_to_frame_end * decay_to_sample;
    axes_.noise_g = phi * axes_.noise_g + axes_.noise_rms_g * SqrtPair(1.0 - phi * phi) * z;
    signal_g += axes_.noise_g;
  }
  axes_.decay_to_frame_end = decay_to_frame_end;
  return signal_g;
}

inline DoublePair Adxl210e::Duty(DoublePair a_g, double dtemp_c, double dsupply_v) const {
  const double dtemp2 = dtemp_c * dtemp_c;
  const double dtemp3 = dtemp2 * dtemp_c;
  DoublePair zero_g = axes_.zero_g_duty_ratio;
  if (effects_.zero_g_tempco) {
    zero_g += axes_.zero_g_tc_ratio[0] * dtemp_c + axes_.zero_g_tc_ratio[1] * dtemp2 +
              axes_.zero_g_tc_ratio[2] * dtemp3;
  }
  if (effects_.supply_sensitivity) zero_g += axes_.supply_ratio_per_v * dsupply_v;
  DoublePair sensitivity = axes_.sensitivity_ratio_per_g;
  if (effects_.sensitivity_tempco) {
    sensitivity *= 1.0 + axes_.sensitivity_tc[0] * dtemp_c + axes_.sensitivity_tc[1] * dtemp2 +
                   axes_.sensitivity_tc[2] * dtemp3;
  }
  const DoublePair a_nl_g = effects_.nonlinearity ? a_g + axes_.quadratic_per_g * a_g * a_g : a_g;
  return ClampPair(zero_g + sensitivity * a_nl_g, 0.0, 1.0);
}

inline Adxl210e::Frame Adxl210e::BeginFrame(const Adxl210eInput& input) {
  // The frame's Gaussian draws come first, while little else is live: a draw's rare slow path
  // calls libm, and values live across it would be saved and restored around every draw.
  std::array<double, 2> z_jitter = {0.0, 0.0};  // the period walk, the reported period
  if (t2_jitter_ratio_ > 0.0) z_jitter = jitter_rng_.NormalPair();
  Frame frame;
  frame.z = DoublePair{0.0, 0.0};
  if (effects_.noise) {
    const std::array<double, 2> z_noise = noise_rng_.NormalPair();
    frame.z = DoublePair{z_noise[0], z_noise[1]};
  }

  frame.dtemp_c = input.die_temp_c - kReferenceTemp_c;
  frame.dsupply_v = input.supply_v - kNominalSupply_v;
  const double t2_cnt = t2_25_cnt_ * (1.0 + t2_tc_per_c_ * frame.dtemp_c);
  frame.period = dcm_.NextFrame(t2_cnt, t2_cnt * t2_jitter_ratio_, z_jitter[0], z_jitter[1]);

  // Cross-axis matrix applied to f_C (identity when the effect is off: the ratios are zero).
  frame.a_in_g = DoublePair{input.f_x_g, input.f_y_g} +
                 axes_.cross_other_ratio * DoublePair{input.f_y_g, input.f_x_g} +
                 axes_.cross_z_ratio * input.f_z_g;
  if (!started_) {
    axes_.filter_g = frame.a_in_g;
    started_ = true;
  }
  return frame;
}

inline Adxl210eOutput Adxl210e::FinishFrame(const Frame& frame) const {
  const DcmPeriod& period = frame.period;
  const DoublePair fall_cnt =
      period.start_cnt + Duty(frame.a_g, frame.dtemp_c, frame.dsupply_v) * period.length_cnt;

  const bool quantize = effects_.capture_quantization;
  const double end_cnt = period.start_cnt + period.length_cnt;
  const uint16_t t2_capture_cnt =
      CaptureIntervalCnt(period.grid_phase_cnt, period.start_cnt, end_cnt, quantize);
  uint16_t t1_capture_cnt[2];
  if (quantize) {
    // CaptureIntervalCnt for both falling edges at once: the edges' tick counts as doubles, exact
    // integers far below 2^51, so the difference is the same integer.
    const DoublePair ticks =
        FloorPair(period.grid_phase_cnt + fall_cnt) -
        static_cast<double>(FloorToInt64(period.grid_phase_cnt + period.start_cnt));
    for (int lane = 0; lane < 2; ++lane) {
      t1_capture_cnt[lane] =
          static_cast<uint16_t>(static_cast<uint64_t>(static_cast<int64_t>(ticks[lane])) & 0xFFFFu);
    }
  } else {
    for (int lane = 0; lane < 2; ++lane) {
      t1_capture_cnt[lane] =
          CaptureIntervalCnt(period.grid_phase_cnt, period.start_cnt, fall_cnt[lane], false);
    }
  }
  return {{t1_capture_cnt[0], t2_capture_cnt}, {t1_capture_cnt[1], t2_capture_cnt}};
}

Adxl210eOutput Adxl210e::Step(const Adxl210eInput& input) {
  Frame frame = BeginFrame(input);
  frame.a_g = FilteredAccel(frame.a_in_g, frame.period.start_cnt, frame.z);
  return FinishFrame(frame);
}

void Adxl210e::StepEach(std::span<Adxl210e> chips,
                        std::span<const Adxl210eInput> inputs,
                        std::span<Adxl210eOutput> outputs) {
  constexpr size_t kMaxChipsPerPass = 4;  // a unit has 3; the frames stay on the stack
  for (size_t first = 0; first < chips.size(); first += kMaxChipsPerPass) {
    const size_t n = std::min(kMaxChipsPerPass, chips.size() - first);
    Frame frames[kMaxChipsPerPass];
    for (size_t k = 0; k < n; ++k) frames[k] = chips[first + k].BeginFrame(inputs[first + k]);
    for (size_t k = 0; k < n; ++k) {
      Frame& f = frames[k];
      f.a_g = chips[first + k].FilteredAccel(f.a_in_g, f.period.start_cnt, f.z);
    }
    for (size_t k = 0; k < n; ++k) outputs[first + k] = chips[first + k].FinishFrame(frames[k]);
  }
}

}  // namespace adahrs::sensor_sim
