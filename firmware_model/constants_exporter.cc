#include "firmware_model/constants_exporter.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

// fmt header-only: firmware_model links no formatting library (firmware_model/CMakeLists.txt).
#define FMT_HEADER_ONLY
#include <fmt/format.h>

#include "firmware_model/air_data_law.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {
namespace {

using Real = long double;

double Lsb(int exponent) { return std::ldexp(1.0, exponent - 31); }

// Smallest e >= min_e with |v| < 2^e (mantissa rounded to nearest stays below 2^31).
CoeffQ31 Quantise(Real v, int min_e, const std::string& what) {
  int e = min_e;
  if (v != 0) {
    int ex = 0;
    std::frexp(static_cast<double>(v), &ex);
    e = std::max(ex, min_e);
  }
  Real m = std::nearbyint(std::ldexp(v, 31 - e));
  if (std::fabs(m) >= std::ldexp(Real{1}, 31)) {
    ++e;
    m = std::nearbyint(std::ldexp(v, 31 - e));
  }
  if (e > kMaxExponent || e < kMinExponent) {
    throw std::invalid_argument(fmt::format("{}: value {:.6g} needs exponent {} outside {}..{}",
                                            what,
                                            static_cast<double>(v),
                                            e,
                                            kMinExponent,
                                            kMaxExponent));
  }
  return CoeffQ31{static_cast<int32_t>(m), static_cast<int8_t>(e)};
}

Real Value(const CoeffQ31& c) {
  return std::ldexp(static_cast<Real>(c.mantissa_q31), c.exponent - 31);
}

Real Binomial(int n, int k) {
  Real r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Coefficients of p(v) = sum k_j (v - v0)^j in x with v = centre + 2^shift x.
std::vector<Real> Renormalise(const std::vector<Real>& k, Real centre_minus_v0, int shift) {
  const int n = static_cast<int>(k.size());
  std::vector<Real> c(n, 0);
  for (int m = 0; m < n; ++m) {
    for (int j = m; j < n; ++j) {
      c[m] +=
          k[j] * Binomial(j, m) * std::pow(centre_minus_v0, j - m) * std::ldexp(Real{1}, shift * m);
    }
  }
  return c;
}

// Normalisation of a thermal fit's temperature counts: centred in the span the fit covers, with
// the smallest power-of-two half-range (at most 2^16) that holds kThermalSpanMargin times the
// span's half-width. The target evaluates xi only inside it, so the polynomial is bounded where it
// was fitted rather than over the whole uint16 domain (where a cubic's extrapolation would not fit
// the channel's U range), and a unit running a little beyond its calibrated temperatures still
// gets the polynomial; beyond the range the target holds xi and flags the input.
constexpr Real kThermalSpanMargin = 1.25;

InputNormQ31 ThermalNorm(const ThermalFit& f, const std::string& what) {
  if (!(f.temp_min_cnt >= 0 && f.temp_min_cnt < f.temp_max_cnt && f.temp_max_cnt <= 65535)) {
    throw std::invalid_argument(
        fmt::format("{}: temperature span {} .. {} counts is not an "
                    "increasing span inside 0..65535",
                    what,
                    f.temp_min_cnt,
                    f.temp_max_cnt));
  }
  const Real centre = std::nearbyint((Real{f.temp_min_cnt} + Real{f.temp_max_cnt}) / 2);
  const Real half_width =
      std::max(centre - Real{f.temp_min_cnt}, Real{f.temp_max_cnt} - centre) * kThermalSpanMargin;
  int shift = 0;
  while (shift < 16 && std::ldexp(Real{1}, shift) < half_width) ++shift;
  return InputNormQ31{static_cast<int32_t>(centre), static_cast<uint8_t>(shift)};
}

struct QuantisedPoly {
  PolyQ31 poly;
  double bound;  // worst-case |error| at |x| <= 1, output units
};

// Quantises c (degree = size - 1) with the smallest working exponent in [min_work, max_work] that
// satisfies the target's overflow rule after rounding.
QuantisedPoly QuantisePoly(const std::vector<Real>& c,
                           int min_work,
                           int max_work,
                           const std::string& what) {
  Real sum_abs = 0;
  for (Real v : c) sum_abs += std::fabs(v);
  int work = min_work;
  while (work <= max_work && std::ldexp(Real{1}, work) <= sum_abs) ++work;
  const uint8_t degree = static_cast<uint8_t>(c.size() - 1);
  for (; work <= max_work; ++work) {
    QuantisedPoly q{};
    q.poly.work_exponent = static_cast<int8_t>(work);
    for (auto& coeff : q.poly.coeff) coeff = CoeffQ31{0, q.poly.work_exponent};
    double coeff_error = 0;
    for (size_t i = 0; i < c.size(); ++i) {
      q.poly.coeff[i] = Quantise(c[i], work - kMaxAlignShift, what);
      coeff_error += static_cast<double>(std::fabs(Value(q.poly.coeff[i]) - c[i]));
    }
    if (ValidatePoly(q.poly, degree) == ConstantsStatus::kOk) {
      q.bound = coeff_error + 4.0 * (degree + 1) * Lsb(work);
      return q;
    }
  }
  throw std::invalid_argument(fmt::format(
      "{}: sum of |coefficients| {:.6g} over the normalised span does not fit below 2^{}",
      what,
      static_cast<double>(sum_abs),
      max_work));
}

// A scale-factor sensor's normalisation: centred at the origin, the smallest power-of-two
// half-range (at most 2^16) holding kThermalSpanMargin times the span's larger side.
InputNormQ31 ScaleSensorNorm(const TempSensorSpan& span, const std::string& what) {
  if (!(span.min_cnt >= 0 && span.min_cnt <= span.origin_cnt && span.origin_cnt <= span.max_cnt &&
        span.min_cnt < span.max_cnt && span.max_cnt <= 65535 &&
        span.origin_cnt == std::nearbyint(span.origin_cnt))) {
    throw std::invalid_argument(
        fmt::format("{}: span {} .. {} about origin {} counts is not an "
                    "increasing span in 0..65535 about a whole count",
                    what,
                    span.min_cnt,
                    span.max_cnt,
                    span.origin_cnt));
  }
  const Real half_width = std::max(Real{span.origin_cnt} - Real{span.min_cnt},
                                   Real{span.max_cnt} - Real{span.origin_cnt}) *
                          kThermalSpanMargin;
  int shift = 0;
  while (shift < 16 && std::ldexp(Real{1}, shift) < half_width) ++shift;
  return InputNormQ31{static_cast<int32_t>(span.origin_cnt), static_cast<uint8_t>(shift)};
}

// Error bounds the format-3 stages add, in output units.
struct ScaleTemperatureBounds {
  double factor = 0.0;          // worst |F - F_exported| over the normalised span
  double factor_max = 1.0;      // worst |F| over it
  double quadratic_gain = 1.0;  // d(ca + q ca^2)/d(ca) at the rated input
  double quadratic_g = 0.0;     // quantisation of q at the rated input, g
};

// What the target's Q15 form of GS adds (deg/s): each element's rounding at its row's exponent
// times the rated input, A rounded to Q15 (1/2 LSB at kAccelMps2Exponent) times the row, and the
// row sum's alignment (1 LSB).
double GSensitivityQ15Bound(const ScaleTemperatureConstantsQ31& st,
                            const std::array<std::array<double, 3>, 3>& gs) {
  double worst = 0;
  for (int r = 0; r < 3; ++r) {
    const double lsb = std::ldexp(1.0, st.gs_q15.row_exponent[r] - 15);
    double row_abs = 0;
    for (int c = 0; c < 3; ++c) row_abs += std::fabs(gs[r][c]);
    worst =
        std::max(worst,
                 3 * 0.5 * lsb * kRatedAccel_mps2 +
                     row_abs * 0.5 * std::ldexp(1.0, kAccelMps2Exponent - 15) + Lsb(kRateExponent));
  }
  return worst;
}

ScaleTemperatureBounds ExportScaleTemperature(const ImuScaleTemperature& in,
                                              const ThermalConstantsQ31 thermal[kImuChannels],
                                              ScaleTemperatureConstantsQ31* out) {
  ScaleTemperatureBounds b{};
  if (!in.active) return b;
  out->enabled = 1;
  for (int s = 0; s < kTempSensors; ++s) {
    out->temp_norm[s] = ScaleSensorNorm(
        in.sensor[s],
        fmt::format("scale switch block 0x{:02X} (sensor {})", kImuBlockScaleSwitch, s));
  }
  b.factor_max = 0.0;
  for (int ch = 0; ch < kImuChannels; ++ch) {
    const std::string what =
        fmt::format("scale factor block 0x{:02X} (channel {})", kImuBlockScaleFactorFirst + ch, ch);
    const InputNormQ31& norm = out->temp_norm[thermal[ch].temp_sensor];
    const auto& f = in.scale[ch];
    const auto c = Renormalise({f[0], f[1], f[2], f[3]}, 0, norm.shift);
    const QuantisedPoly poly = QuantisePoly(c, kScaleFactorExponent, kScaleFactorExponent, what);
    out->scale[ch] = poly.poly;
    Real sum_abs = 0;
    for (Real v : c) sum_abs += std::fabs(v);
    // The target runs F as 1 + delta at delta's Q15 exponent: d1..d3 rounded (1/2 LSB each, at
    // most as coarse), tau rounded (1/2 2^-16 for shift 16) and its square and cube (2^-16 and
    // 2^-15, times sum |d_k| < 2^exponent: 1.5 LSB) and delta itself (1/2 LSB): within 4 LSB.
    ScaleDeltaQ15 delta{};
    DeriveScaleDelta(poly.poly, &delta);
    b.factor = std::max(b.factor, poly.bound + 4 * std::ldexp(1.0, delta.exponent - 15));
    b.factor_max = std::max(b.factor_max, static_cast<double>(sum_abs));
  }
  const double rated_g = kRatedAccel_g;
  for (int axis = 0; axis < 3; ++axis) {
    const std::string what = fmt::format(
        "accelerometer nonlinearity block 0x{:02X} (axis {})", kImuBlockAccelQuadratic, axis);
    const double q = in.accel_quadratic_per_g[axis];
    if (std::fabs(q) >= 1.0 / 16.0) {
      throw std::invalid_argument(fmt::format("{}: |q| = {:.4g} g/g^2 is not below 1/16", what, q));
    }
    out->accel_quadratic[axis] = Quantise(q, -kAccelGExponent - kMaxAlignShift, what);
    const double dq = static_cast<double>(std::fabs(Value(out->accel_quadratic[axis]) - q));
    b.quadratic_gain = std::max(b.quadratic_gain, 1.0 + 2.0 * std::fabs(q) * rated_g);
    // The target's Q15 form: q rounded (1/2 LSB of its high word), ca rounded to Q15 before the
    // square (2 |ca| times 1/2 LSB at kAccelGExponent) and the square rounded (1/2 LSB at twice
    // it).
    const double q15 = std::ldexp(1.0, out->accel_quadratic[axis].exponent - 16);
    const double square_g2 = 2 * rated_g * std::ldexp(1.0, kAccelGExponent - 16) +
                             std::ldexp(1.0, 2 * kAccelGExponent - 16);
    b.quadratic_g = std::max(
        b.quadratic_g,
        (dq + q15) * rated_g * rated_g + std::fabs(q) * square_g2 + 8 * Lsb(kAccelGExponent));
  }
  return b;
}

// The thermal blocks 0x01-0x09; each channel's bound on its drift-corrected output, in its own
// units (duty or counts).
std::array<double, kImuChannels> ExportThermal(const ImuCalibrationConstants& in, ImuConstants& q) {
  std::array<double, kImuChannels> thermal_bound{};
  for (int ch = 0; ch < kImuChannels; ++ch) {
    const std::string what = fmt::format("thermal block 0x{:02X} (channel {})", ch + 1, ch);
    const ThermalFit& f = in.thermal[ch];
    if (f.temp_sensor < 0 || f.temp_sensor >= kTempSensors) {
      throw std::invalid_argument(what + ": temp_sensor must be 0..2");
    }
    ThermalConstantsQ31& t = q.thermal[ch];
    t.temp_sensor = static_cast<uint8_t>(f.temp_sensor);
    t.temp_norm = ThermalNorm(f, what);
    const int u_e = ch < kAccelChannels ? kDutyExponent : kGyroCountExponent;
    const auto c =
        Renormalise({f.k[0], f.k[1], f.k[2], f.k[3]}, t.temp_norm.centre, t.temp_norm.shift);
    const QuantisedPoly poly = QuantisePoly(c, u_e - kMaxAlignShift, u_e, what);
    t.drift = poly.poly;
    DeriveThermalAligned(&t);
    thermal_bound[ch] = poly.bound + 2 * Lsb(u_e);
  }
  return thermal_bound;
}

// The accelerometer block 0x0A; the worst sensor-calibrated acceleration bound, g.
double ExportAccel(const ImuCalibrationConstants& in,
                   const std::array<double, kImuChannels>& thermal_bound,
                   ImuConstants& q) {
  double accel_g = 0;
  for (int ch = 0; ch < kAccelChannels; ++ch) {
    const std::string what = fmt::format("accelerometer block 0x0A (channel {})", ch);
    const AccelScaleFit& a = in.accel[ch];
    if (std::fabs(a.offset_duty) >= 0.5 || a.scale_duty_per_g == 0) {
      throw std::invalid_argument(fmt::format("{}: offset {} duty or scale {} duty/g unusable",
                                              what,
                                              a.offset_duty,
                                              a.scale_duty_per_g));
    }
    const Real inv_scale = Real{1} / a.scale_duty_per_g;
    q.accel[ch].offset_duty_q31 =
        static_cast<int32_t>(std::nearbyint(std::ldexp(a.offset_duty, 31)));
    q.accel[ch].inv_scale_g = Quantise(inv_scale, kAccelGExponent - kMaxAlignShift, what);
    if (std::fabs(inv_scale) * 0.5 >= 16.0) {
      throw std::invalid_argument(fmt::format(
          "{}: |1/S| = {:.4g} g/duty overflows +-16 g", what, static_cast<double>(inv_scale)));
    }
    const double bound =
        (thermal_bound[ch] + Lsb(kDutyExponent)) * std::fabs(1 / a.scale_duty_per_g) +
        0.5 * static_cast<double>(std::fabs(Value(q.accel[ch].inv_scale_g) - inv_scale)) +
        4 * Lsb(kAccelGExponent);
    accel_g = std::max(accel_g, bound);
  }
  return accel_g;
}

// The gyro cubic blocks; the worst sensor-calibrated rate bound, deg/s.
double ExportGyro(const ImuCalibrationConstants& in,
                  const std::array<double, kImuChannels>& thermal_bound,
                  ImuConstants& q) {
  double rate_dps = 0;
  for (int g = 0; g < kGyroChannels; ++g) {
    const std::string what = fmt::format("gyro block 0x{:02X}", kImuBlockGyroCubicFirst + g);
    const GyroCubicFit& f = in.gyro[g];
    GyroCubicConstantsQ31& gq = q.gyro[g];
    const Real centre_q = std::nearbyint(std::ldexp(static_cast<Real>(f.null_cnt), 8));
    if (std::fabs(centre_q) >= std::ldexp(Real{1}, 31)) {
      throw std::invalid_argument(
          fmt::format("{}: null {} counts outside +-2^23", what, f.null_cnt));
    }
    gq.count_norm = InputNormQ31{static_cast<int32_t>(centre_q), 22};
    const Real centre_cnt = std::ldexp(centre_q, -8);
    const auto c = Renormalise({f.l[0], f.l[1], f.l[2], f.l[3]}, centre_cnt - f.null_cnt, 22);
    const QuantisedPoly poly = QuantisePoly(c, kRateExponent, kRateExponent, what);
    gq.rate = poly.poly;
    // d(rate)/d(count) over the span bounds how a thermal error in counts shows in deg/s.
    const Real span = std::ldexp(Real{1}, 22);
    const double slope = static_cast<double>(std::fabs(f.l[1]) + 2 * std::fabs(f.l[2]) * span +
                                             3 * std::fabs(f.l[3]) * span * span);
    rate_dps = std::max(rate_dps, poly.bound + thermal_bound[kAccelChannels + g] * slope);
  }
  return rate_dps;
}

// A 3x3 matrix block at exponent out_e; its output's worst bound for inputs up to `rated` known to
// within in_bound.
double ExportMatrix(const std::array<std::array<double, 3>, 3>& m,
                    CoeffQ31 out_m[3][3],
                    int out_e,
                    double rated,
                    double in_bound,
                    const std::string& what) {
  double worst = 0;
  for (int r = 0; r < 3; ++r) {
    double row_abs = 0;
    double row_err = 0;
    for (int c = 0; c < 3; ++c) {
      out_m[r][c] = Quantise(m[r][c], out_e - kMaxAlignShift, what);
      row_abs += std::fabs(m[r][c]);
      row_err += static_cast<double>(std::fabs(Value(out_m[r][c]) - m[r][c]));
    }
    if (row_abs * rated >= std::ldexp(1.0, out_e)) {
      throw std::invalid_argument(
          fmt::format("{}: row {} sum |C| = {:.6g} times the rated input {} overflows +-2^{}",
                      what,
                      r,
                      row_abs,
                      rated,
                      out_e));
    }
    worst = std::max(worst, row_err * rated + row_abs * in_bound + 6 * Lsb(out_e));
  }
  return worst;
}

// Every block must pass the target's own validation, so host and target agree on what is valid.
void CheckAgainstTarget(const ImuConstants& q) {
  ImuConstants check{};
  ImuConstantsInit(&check);
  for (uint8_t id = kImuBlockThermalFirst; id <= kImuBlockLast; ++id) {
    int16_t words[kImuMaxBlockWords];
    uint8_t count = 0;
    ImuConstantsReadBlock(&q, id, words, kImuMaxBlockWords, &count);
    const ConstantsStatus status = ImuConstantsWriteBlock(&check, id, words, count);
    if (status != ConstantsStatus::kOk) {
      throw std::invalid_argument(
          fmt::format("IMU block 0x{:02X}: target validation refuses it "
                      "(status {})",
                      id,
                      static_cast<int>(status)));
    }
  }
}

}  // namespace

ImuExport ExportImuConstants(const ImuCalibrationConstants& in) {
  ImuExport out{};
  ImuConstantsInit(&out.constants);
  ImuConstants& q = out.constants;
  const std::array<double, kImuChannels> thermal_bound = ExportThermal(in, q);
  double accel_g = ExportAccel(in, thermal_bound, q);
  double rate_dps = ExportGyro(in, thermal_bound, q);
  const ScaleTemperatureBounds st =
      ExportScaleTemperature(in.scale_temperature, q.thermal, &q.scale_temperature);
  if (in.scale_temperature.active) {
    // y F: the error of y grows by |F|, F's own error by the largest |y|; the product's rounding
    // and the one-bit alignment are 4 LSB.
    accel_g = accel_g * st.factor_max + kRatedAccel_g * st.factor + 4 * Lsb(kAccelGExponent);
    rate_dps = rate_dps * st.factor_max + kRatedRate_dps * st.factor + 4 * Lsb(kRateExponent);
  }
  const double ca_in_g = accel_g * st.quadratic_gain + st.quadratic_g;
  const double ca_bound = ExportMatrix(
      in.ca_mps2_per_g, q.ca, kAccelMps2Exponent, kRatedAccel_g, ca_in_g, "CA block 0x0E");
  double cg_bound =
      ExportMatrix(in.cg, q.cg, kRateExponent, kRatedRate_dps, rate_dps, "CG block 0x0F");
  if (in.scale_temperature.active) {
    cg_bound += ExportMatrix(in.scale_temperature.gs_dps_per_mps2,
                             q.scale_temperature.gs,
                             kRateExponent,
                             kRatedAccel_mps2,
                             ca_bound,
                             "GS block 0x1B") +
                4 * Lsb(kRateExponent);
    DeriveScaleTemperatureQ15(&q.scale_temperature);
    cg_bound += GSensitivityQ15Bound(q.scale_temperature, in.scale_temperature.gs_dps_per_mps2);
  }
  CheckAgainstTarget(q);
  out.report = ImuExportReport{accel_g, rate_dps, ca_bound, cg_bound};
  return out;
}

namespace {

// One operator's inv_span: 0 for a term that is off; otherwise the input exponent plus its
// exponent must lie in -31..31 (docs/firmware-compensator.md "Hysteresis compensation").
CoeffQ31 InverseSpan(double span, int input_exponent, const std::string& what) {
  if (span == 0.0) return CoeffQ31{0, 0};
  const CoeffQ31 inv = Quantise(1.0L / span, kMinExponent, what);
  if (inv.mantissa_q31 == INT32_MIN || input_exponent + inv.exponent < -31 ||
      input_exponent + inv.exponent > 31) {
    throw std::invalid_argument(
        fmt::format("{}: span {:.6g} is outside what the operator's travel can carry", what, span));
  }
  return inv;
}

// A gain at_centre + per_tau tau in Q15 at the smallest exponent (from result_e - 16 up) for which
// |at_centre| + |per_tau| stays within Q15 (|tau| < 1); refused above the result's full scale.
GainQ15 QuantiseGain(double at_centre, double per_tau, int result_e, const std::string& what) {
  auto q15 = [](double v, int e) { return std::nearbyint(std::ldexp(v, 15 - e)); };
  int e = result_e - kMaxAlignShift;
  while (e <= result_e && std::fabs(q15(at_centre, e)) + std::fabs(q15(per_tau, e)) > 32767.0) ++e;
  if (e > result_e) {
    throw std::invalid_argument(
        fmt::format("{}: gain {:.6g} + {:.6g} tau exceeds the result's full "
                    "scale 2^{}",
                    what,
                    at_centre,
                    per_tau,
                    result_e));
  }
  return GainQ15{static_cast<int16_t>(q15(at_centre, e)),
                 static_cast<int16_t>(q15(per_tau, e)),
                 static_cast<int8_t>(e)};
}

double Q15Lsb(int exponent) { return std::ldexp(1.0, exponent - 15); }

// The hysteresis terms of surface `q` (its y normalisation already chosen) whose result is at
// `result_e`. The die temperature T(y) is re-expanded in the normalised y and scaled by the
// smallest power of two K (degC) that keeps sum |t_k| within Q15 with a 1 % margin: tau =
// (T - T_c) / K, T_c the temperature at the normalisation's centre (the operator sees only
// differences of tau; the gains are re-centred on T_c). inv_span = K / span. Returns the terms'
// contribution to the error bound against the double reference fed the same states and the exact
// die temperature: per gain, its rounding (1 LSB each part), tau's (Horner, 3 LSB of K degC) times
// its slope, the Q15 gain's and state's roundings (2 + 4 LSB of the gain), the alignment (1 LSB).
double ExportHysteresis(const HysteresisCompensation& h,
                        int result_e,
                        const std::string& what,
                        SurfaceQ31* q) {
  for (int16_t& t : q->die_temp_q15) t = 0;
  Real centre_c = kHysteresisGainReferenceC;
  Real scale_c = 1;
  if (h.die_temp_c[1] != 0.0 || h.die_temp_c[2] != 0.0 || h.die_temp_c[3] != 0.0) {
    const std::vector<Real> k(h.die_temp_c.begin(), h.die_temp_c.end());
    const std::vector<Real> c =
        Renormalise(k,
                    static_cast<Real>(q->y_norm.centre) - static_cast<Real>(h.die_temp_origin_code),
                    q->y_norm.shift);
    const Real sum = std::fabs(c[1]) + std::fabs(c[2]) + std::fabs(c[3]);
    int scale_e = -8;
    while (sum >= 0.99L * std::ldexp(Real{1}, scale_e)) ++scale_e;
    if (scale_e > 16) {
      throw std::invalid_argument(
          fmt::format("{}: die temperature spans {:.6g} degC over the code box, beyond tau's range",
                      what,
                      static_cast<double>(sum)));
    }
    for (int m = 1; m <= 3; ++m) {
      q->die_temp_q15[m - 1] = static_cast<int16_t>(std::nearbyint(std::ldexp(c[m], 15 - scale_e)));
    }
    centre_c = c[0];
    scale_c = std::ldexp(Real{1}, scale_e);
  }
  auto term =
      [&](double gain, double per_c, double inv_span_input, int input_e, const std::string& name) {
        const Real at_centre = Real{gain} + Real{per_c} * (centre_c - kHysteresisGainReferenceC);
        const HysteresisTermQ t{InverseSpan(inv_span_input, input_e, what + " " + name + " span"),
                                QuantiseGain(static_cast<double>(at_centre),
                                             static_cast<double>(per_c * scale_c),
                                             result_e,
                                             what + " " + name)};
        return t;
      };
  q->pressure = term(h.pressure_gain, h.pressure_gain_per_c, h.pressure_span, result_e, "pressure");
  q->thermal = term(h.thermal_gain,
                    h.thermal_gain_per_c,
                    static_cast<double>(h.thermal_span_c / scale_c),
                    0,
                    "thermal");
  double bound = 0.0;
  for (const auto& [g, slope, c] :
       {std::tuple{h.pressure_gain, h.pressure_gain_per_c, q->pressure.gain},
        std::tuple{h.thermal_gain, h.thermal_gain_per_c, q->thermal.gain}}) {
    const double lsb = Q15Lsb(c.exponent);
    bound += 2.0 * lsb + std::fabs(slope) * 3.0 * static_cast<double>(scale_c) / 32768.0 +
             6.0 * lsb + (std::fabs(g) + std::fabs(slope) * 65.0) * 4.0 / 32768.0 + Lsb(result_e);
  }
  return bound;
}

// The smallest shift with 2^shift > half: the power-of-two half-width of a code normalisation.
int HalfWidthShift(double half) {
  int shift = 0;
  while (std::ldexp(1.0, shift) <= half) ++shift;
  return shift;
}

// The target's form of a surface's linearisation (bridge_linearisation.h): the raw normalisation
// centred on the origin with the smallest power-of-two half-width that holds the bridge codes
// whose linearised codes bound the surface's y box (y - origin = d + kappa d^2 / 4, d = s -
// origin), and k = kappa 2^shift in Q13. Off: the code itself.
BridgeLinearisationQ ExportLinearisation(const SurfaceFit& s, const std::string& what) {
  const BridgeLinearisation& l = s.y_linearisation;
  if (!l.active()) return BridgeLinearisationQ{InputNormQ31{0, 23}, 0};
  constexpr double kCodeLimit = 16777216.0;  // the ADS1254's 2^24
  if (l.origin_code != std::nearbyint(l.origin_code) || std::fabs(l.origin_code) >= kCodeLimit) {
    throw std::invalid_argument(
        fmt::format("{}: linearisation origin {} is not a whole 24-bit code", what, l.origin_code));
  }
  auto raw_offset = [&](double s_code) {
    const double d = s_code - l.origin_code;
    return d + l.curvature_per_code * d * d / 4.0;
  };
  const int shift = HalfWidthShift(
      std::max(std::fabs(raw_offset(s.y_min_code)), std::fabs(raw_offset(s.y_max_code))));
  const double k_q13 = std::nearbyint(std::ldexp(l.curvature_per_code, shift + 13));
  // sqrt(1 + kappa (y - origin)) = 1 + kappa d / 2 must stay positive over the box (the root's
  // own branch).
  const bool principal = 1.0 + l.curvature_per_code * (s.y_min_code - l.origin_code) / 2.0 > 0.0 &&
                         1.0 + l.curvature_per_code * (s.y_max_code - l.origin_code) / 2.0 > 0.0;
  if (shift > 24 || std::fabs(k_q13) > INT16_MAX || !principal) {
    throw std::invalid_argument(fmt::format(
        "{}: bridge curvature {:.4g} per code over a half-width of 2^{} codes is beyond the "
        "target's |k| < 4 (or its 2^24 codes, or turns inside the y box)",
        what,
        l.curvature_per_code,
        shift));
  }
  return BridgeLinearisationQ{
      InputNormQ31{static_cast<int32_t>(l.origin_code), static_cast<uint8_t>(shift)},
      static_cast<int16_t>(k_q13)};
}

// The linearised code's error against the double's, in codes: the quotient's LSB 2^(shift - 14),
// the root's truncation (2^-14 of v at most), the divisor's (2^-13 of v) and k's rounding (2^-16
// of v, which also bounds a k that rounds to 0): 4 quotient LSBs bound them. 0 when off.
double LinearisedCodeError(const SurfaceFit& s, const BridgeLinearisationQ& l) {
  return s.y_linearisation.active() ? 4.0 * std::ldexp(1.0, l.raw_norm.shift - 14) : 0.0;
}

}  // namespace

AdsExport ExportAdsConstants(const AdsCalibrationConstants& in) {
  AdsExport out{};
  AdsConstantsInit(&out.constants);
  auto export_surface = [](const SurfaceFit& s, int out_e, const std::string& what, SurfaceQ31* q) {
    auto norm = [&](double lo, double hi, const char* axis) {
      const double centre = std::nearbyint(0.5 * (lo + hi));
      const int shift = HalfWidthShift(std::max(hi - centre, centre - lo));
      if (shift > 31 || std::fabs(centre) >= std::ldexp(1.0, 31)) {
        throw std::invalid_argument(
            fmt::format("{}: {} code box [{}, {}] too wide", what, axis, lo, hi));
      }
      return InputNormQ31{static_cast<int32_t>(centre), static_cast<uint8_t>(shift)};
    };
    q->x_norm = norm(s.x_min_code, s.x_max_code, "x");
    q->y_norm = norm(s.y_min_code, s.y_max_code, "y");
    q->y_linearisation = ExportLinearisation(s, what);
    constexpr int kPx = kSurfaceXDegree, kQy = kSurfaceYDegree;
    static_assert(kPx == kAdsSurfaceXDegree && kQy == kAdsSurfaceYDegree);
    const Real cx = q->x_norm.centre, cy = q->y_norm.centre;
    const Real hx = std::ldexp(Real{1}, q->x_norm.shift), hy = std::ldexp(Real{1}, q->y_norm.shift);
    Real norm_c[kPx + 1][kQy + 1] = {};  // coefficient of X^m Y^n
    for (int m = 0; m <= kPx; ++m) {
      for (int n = 0; n <= kQy; ++n) {
        for (int p = m; p <= kPx; ++p) {
          for (int r = n; r <= kQy; ++r) {
            norm_c[m][n] += Real{s.coeff_xy[p][r]} * Binomial(p, m) * std::pow(cx, p - m) *
                            std::pow(hx, m) * Binomial(r, n) * std::pow(cy, r - n) *
                            std::pow(hy, n);
          }
        }
      }
    }
    // Outer exponent E: the smallest (from the output exponent - 16 up) for which every b_k,
    // quantised with a working exponent within 16 of E, satisfies sum_k 2^(E_k) <= 2^E.
    for (int e = out_e - kMaxAlignShift; e <= out_e + kMaxAlignShift; ++e) {
      double bound = 0;
      Real sum = 0;
      bool aligned = true;
      for (int k = 0; k <= kPx; ++k) {
        std::vector<Real> c(norm_c[k], norm_c[k] + kQy + 1);
        Real sum_abs = 0;
        for (Real v : c) sum_abs += std::fabs(v);
        if (sum_abs >= std::ldexp(Real{1}, e)) {
          aligned = false;
          break;
        }
        const QuantisedPoly b =
            QuantisePoly(c, e - kMaxAlignShift, e, fmt::format("{} b{}(y)", what, k));
        q->b[k] = b.poly;
        bound += b.bound;
        sum += std::ldexp(Real{1}, b.poly.work_exponent);
      }
      if (aligned && sum <= std::ldexp(Real{1}, e)) {
        q->outer_work_exponent = static_cast<int8_t>(e);
        Real slope_per_code = 0;  // |dz/dy| over the box
        for (int m = 0; m <= kPx; ++m) {
          for (int n = 1; n <= kQy; ++n) slope_per_code += n * std::fabs(norm_c[m][n]) / hy;
        }
        return bound + 4 * kPx * Lsb(e) + Lsb(out_e) +
               ExportHysteresis(s.hysteresis, out_e, what, q) +
               static_cast<double>(slope_per_code) * LinearisedCodeError(s, q->y_linearisation);
      }
    }
    throw std::invalid_argument(
        fmt::format("{}: the surface's partial sums need more than 2^{} (output format 2^{})",
                    what,
                    out_e + kMaxAlignShift,
                    out_e));
  };
  // Under a law the surface gives Pa; its bound is carried to the output through the law's
  // steepest slope in the envelope (at 51,000 ft, and at 25 kt: the envelope's 30 kt less a margin
  // for the surface's own error), plus the table's interpolation error (air_data_law.h:
  // h'' (128 Pa)^2 / 8 = 0.36 ft at 11 kPa; |d2(CAS^2)/dqc^2| (256 Pa)^2 / 8 = 0.36 kt^2, i.e.
  // 0.007 kt at 25 kt), the square root's 1/128 kt and the output's resolution.
  const bool isa = in.altitude_ft.law == SurfaceLaw::kIsaAltitude;
  const bool cas = in.airspeed_kt.law == SurfaceLaw::kCas;
  const double alt_bound = export_surface(in.altitude_ft,
                                          isa ? kPressureExponent : kAltitudeExponent,
                                          "altitude block 0x21",
                                          &out.constants.altitude);
  const double cas_bound = export_surface(in.airspeed_kt,
                                          cas ? kPressureExponent : kAirspeedExponent,
                                          "airspeed block 0x22",
                                          &out.constants.airspeed);
  out.constants.altitude.law = isa ? kAdsLawIsaAltitude : kAdsLawDirect;
  out.constants.airspeed.law = cas ? kAdsLawCas : kAdsLawDirect;
  constexpr double kLowestStaticPa = 11000.0, kLowestImpactPa = 101.0, kLowestCasKt = 25.0;
  const double ft_per_pa = IsaAltitudeFtFromStaticPa(kLowestStaticPa - 0.5) -
                           IsaAltitudeFtFromStaticPa(kLowestStaticPa + 0.5);
  const double kt_per_pa =
      CasKtFromImpactPa(kLowestImpactPa + 0.5) - CasKtFromImpactPa(kLowestImpactPa - 0.5);
  out.report.altitude_ft = isa ? alt_bound * ft_per_pa + 0.36 + Lsb(kAltitudeExponent) : alt_bound;
  out.report.airspeed_kt = cas ? cas_bound * kt_per_pa + 0.36 / (2.0 * kLowestCasKt) + 1.0 / 128.0 +
                                     Lsb(kAirspeedExponent)
                               : cas_bound;
  AdsConstants check{};
  AdsConstantsInit(&check);
  for (uint8_t id : {uint8_t{kAdsBlockAltitude}, uint8_t{kAdsBlockAirspeed}}) {
    int16_t words[kAdsMaxBlockWords];
    uint8_t count = 0;
    AdsConstantsReadBlock(&out.constants, id, words, kAdsMaxBlockWords, &count);
    const ConstantsStatus status = AdsConstantsWriteBlock(&check, id, words, count);
    if (status != ConstantsStatus::kOk) {
      throw std::invalid_argument(
          fmt::format("ADS block 0x{:02X}: target validation refuses it "
                      "(status {})",
                      id,
                      static_cast<int>(status)));
    }
  }
  return out;
}

}  // namespace adahrs::firmware_model
