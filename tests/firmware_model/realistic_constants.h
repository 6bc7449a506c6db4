// Test fixtures: calibration constants of realistic magnitude (reference-method.md "Scales implied
// by the reference tables") and raw frames synthesised from physical truth over the envelope.
// Magnitudes: accelerometer 1/S = +-25.08..25.93 g per duty with the reference's channel signs,
// offsets ~ +-0.01 duty; thermal drift tens of mg and a few deg/s over -40..85 C; gyro null ~4.2e6
// counts, l1 = 4.68..4.84e-5 deg/s per count, l2 ~ 1e-13, l3 ~ 1e-20; cross-axis off-diagonals
// ~0.01. Temperature counts: ADXRS150 TEMP 2.50 V at 25 C, 8.4 mV/K (physics.md 2.1), 16 x 12-bit
// at 5 V: 13,107 counts per volt.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/random.h"
#include "firmware_model/calibration_constants.h"
#include "firmware_model/reference_compensator.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model::testing {

inline constexpr double kGyroCountsPerDps = 20972.0;
inline constexpr double kAccelReciprocalScale_g_per_duty[6] = {
    -25.35, -25.08, 25.26, 25.93, 25.57, -25.71};
// Body axis of each accelerometer channel az1 ax1 ay1 az2 ax2 ay2.
inline constexpr int kAxisOfChannel[6] = {2, 0, 1, 2, 0, 1};

inline double TempCounts(double temp_c) { return 13107.0 * (2.50 + 0.0084 * (temp_c - 25.0)); }

/// A realistic IMU calibration drawn with `seed`.
inline ImuCalibrationConstants RealisticImu(uint64_t seed) {
  common::Rng rng(seed);
  ImuCalibrationConstants c;
  const double t25 = TempCounts(25.0);
  const double cnt_per_c = TempCounts(26.0) - t25;
  for (int ch = 0; ch < 9; ++ch) {
    ThermalFit& f = c.thermal[ch];
    f.temp_sensor = ch < 6 ? ch % 3 : ch - 6;
    // Drift xi(t) = x0 + s1 dT + s2 dT^2 + s3 dT^3, dT = (t - t25) counts: ~ +-40 mg (accel, as
    // duty) or +-3 deg/s (gyro, counts) at the envelope edge 60 C away, fitted over -40..85 C.
    const double edge = 60.0 * cnt_per_c;
    const double full = ch < 6 ? 0.040 / 25.0 : 3.0 * kGyroCountsPerDps;
    const double x0 = ch < 6 ? rng.Uniform(-0.01, 0.01) : 4.2e6 + rng.Uniform(-5e4, 5e4);
    const double s1 = rng.Uniform(-1.0, 1.0) * full / edge;
    const double s2 = rng.Uniform(-0.5, 0.5) * full / (edge * edge);
    const double s3 = rng.Uniform(-0.25, 0.25) * full / (edge * edge * edge);
    f.k = {x0 - s1 * t25 + s2 * t25 * t25 - s3 * t25 * t25 * t25,
           s1 - 2 * s2 * t25 + 3 * s3 * t25 * t25,
           s2 - 3 * s3 * t25,
           s3};
    f.temp_min_cnt = TempCounts(-40.0);
    f.temp_max_cnt = TempCounts(85.0);
  }
  for (int ch = 0; ch < 6; ++ch) {
    c.accel[ch].offset_duty = rng.Uniform(-0.004, 0.004);
    c.accel[ch].scale_duty_per_g = 1.0 / kAccelReciprocalScale_g_per_duty[ch];
  }
  for (int g = 0; g < 3; ++g) {
    c.gyro[g].null_cnt = rng.Uniform(-300.0, 300.0);
    c.gyro[g].l = {rng.Uniform(-0.05, 0.05),
                   rng.Uniform(4.68e-5, 4.84e-5),
                   rng.Uniform(-1e-13, 1e-13),
                   rng.Uniform(-2e-20, 2e-20)};
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      const double off = rng.Uniform(-0.015, 0.015);
      c.ca_mps2_per_g[r][k] = 9.80665 * ((r == k ? 1.0 + rng.Uniform(-0.01, 0.01) : 0.0) + off);
      c.cg[r][k] = (r == k ? 1.0 + rng.Uniform(-0.01, 0.01) : 0.0) + rng.Uniform(-0.015, 0.015);
    }
  }
  return c;
}

/// `c` with the format-3 terms of realistic magnitude drawn with `seed`: scale factors changing by
/// up to +-1.2 % over -40..85 C (ADXRS150 sensitivity tempco, ADXL210E sensitivity tempco; the
/// drift fixture's cubic shape), axis nonlinearity |q| <= 2e-3 g/g^2 (0.2 % FS at 10 g), and gyro
/// g-sensitivity |GS| <= 0.2 deg/s per g on the diagonal-free terms too (physics.md 2.1).
inline ImuCalibrationConstants WithScaleTemperature(ImuCalibrationConstants c, uint64_t seed) {
  common::Rng rng(seed);
  ImuScaleTemperature& st = c.scale_temperature;
  st.active = true;
  const double t25 = std::nearbyint(TempCounts(25.0));
  const double edge = TempCounts(85.0) - t25;
  for (TempSensorSpan& span : st.sensor) span = {t25, TempCounts(-40.0), TempCounts(85.0)};
  for (auto& f : st.scale) {
    f = {1.0 + rng.Uniform(-0.002, 0.002),
         rng.Uniform(-0.010, 0.010) / edge,
         rng.Uniform(-0.003, 0.003) / (edge * edge),
         rng.Uniform(-0.001, 0.001) / (edge * edge * edge)};
  }
  for (double& q : st.accel_quadratic_per_g) q = rng.Uniform(-2e-3, 2e-3);
  for (auto& row : st.gs_dps_per_mps2) {
    for (double& v : row) v = rng.Uniform(-0.2, 0.2) / 9.80665;
  }
  return c;
}

/// Raw frame for specific force f_B_g (body x, y, z), rate w_dps, temperature temp_c, with the
/// sensors behaving as the constants `c` describe (so the calibrated output is near the truth).
inline ImuRawFrame SynthesiseImu(const ImuCalibrationConstants& c,
                                 const std::array<double, 3>& f_B_g,
                                 const std::array<double, 3>& w_dps,
                                 double temp_c,
                                 common::Rng* rng) {
  ImuRawFrame raw{};
  for (int s = 0; s < 3; ++s) {
    raw.temp_cnt[s] =
        static_cast<uint16_t>(std::lround(TempCounts(temp_c) + rng->Uniform(-20, 20)));
  }
  for (int ch = 0; ch < 9; ++ch) {
    const ThermalFit& f = c.thermal[ch];
    const double t = raw.temp_cnt[f.temp_sensor];
    const double xi = f.k[0] + t * (f.k[1] + t * (f.k[2] + t * f.k[3]));
    if (ch < 6) {
      const double u =
          xi + c.accel[ch].offset_duty + c.accel[ch].scale_duty_per_g * f_B_g[kAxisOfChannel[ch]];
      const double t2 = std::floor(rng->Uniform(20000.0, 65000.0));
      raw.t2_cnt[ch] = static_cast<uint16_t>(t2);
      raw.t1_cnt[ch] = static_cast<uint16_t>(std::lround((0.5 + u) * t2));
    } else {
      const int g = ch - 6;
      raw.gyro_cnt[g] =
          static_cast<int32_t>(std::lround(xi + c.gyro[g].null_cnt + w_dps[g] * kGyroCountsPerDps));
    }
  }
  return raw;
}

// ---- ADS: ISA truth (physics.md 4.1) and an ADS1254 code model of the model-1230 bridges.
inline double IsaPressure_pa(double alt_ft) {
  const double h_m = alt_ft * 0.3048;
  const double p11_pa = 101325.0 * std::pow(1.0 - 2.25577e-5 * 11000.0, 5.25588);
  return h_m <= 11000.0 ? 101325.0 * std::pow(1.0 - 2.25577e-5 * h_m, 5.25588)
                        : p11_pa * std::exp(-(h_m - 11000.0) / 6341.62);
}
inline double ImpactPressure_pa(double cas_kt) {
  const double m = cas_kt / 661.4788;
  return 101325.0 * (std::pow(1.0 + 0.2 * m * m, 3.5) - 1.0);
}
// 100 mV full-scale output over 15 psi into a 5 V FSR 24-bit ADC: 167,772 codes per 103,421 Pa,
// with a -0.05 %/C span tempco; bridge voltage ~2 V at 25 C after a divider, +0.26 %/C and
// +8 ppm/C^2 (the bridge resistance's quadratic tempco, pressure_bridge.h).
inline double PressureCode(double p_pa, double temp_c) {
  return 30000.0 + 1.62222 * p_pa * (1.0 - 5e-4 * (temp_c - 25.0)) + 40.0 * (temp_c - 25.0);
}
inline double BridgeCode(double temp_c) {
  const double dt_c = temp_c - 25.0;
  return 6710886.0 * (1.0 + 0.0026 * dt_c + 8e-6 * dt_c * dt_c);
}
// Its linearisation (calibration_constants.h): origin at 25 C, kappa = 4 c / b^2 of the quadratic
// above, so that the linearised code is origin + b (T - 25 C); the pitot's bridge reads 1.01 times
// as much.
inline BridgeLinearisation BridgeCodeLinearisation(double gain) {
  const double b = gain * 6710886.0 * 0.0026, c = gain * 6710886.0 * 8e-6;
  return BridgeLinearisation{std::nearbyint(gain * 6710886.0), 4.0 * c / (b * b)};
}

// Least-squares fit of the surface with `terms` (the reference's 10 by default) to samples
// (x, y, z), in normalised variables
// (X = (x - cx)/hx) solved by normal equations in long double, returned in raw-code form.
inline SurfaceFit FitSurface(const std::vector<std::array<double, 3>>& xyz,
                             const std::vector<XyPowers>& terms = std::vector<XyPowers>(
                                 std::begin(kReferenceCubicTerm), std::end(kReferenceCubicTerm))) {
  SurfaceFit s;
  s.x_min_code = s.y_min_code = 1e300;
  s.x_max_code = s.y_max_code = -1e300;
  for (const auto& p : xyz) {
    s.x_min_code = std::min(s.x_min_code, p[0]);
    s.x_max_code = std::max(s.x_max_code, p[0]);
    s.y_min_code = std::min(s.y_min_code, p[1]);
    s.y_max_code = std::max(s.y_max_code, p[1]);
  }
  const long double cx = 0.5L * (s.x_min_code + s.x_max_code),
                    hx = 0.5L * (s.x_max_code - s.x_min_code);
  const long double cy = 0.5L * (s.y_min_code + s.y_max_code),
                    hy = 0.5L * (s.y_max_code - s.y_min_code);
  const size_t nt = terms.size();
  std::vector<std::vector<long double>> n(nt, std::vector<long double>(nt + 1, 0.0L));
  std::vector<long double> phi(nt);
  for (const auto& p : xyz) {
    const long double X = (p[0] - cx) / hx, Y = (p[1] - cy) / hy;
    for (size_t t = 0; t < nt; ++t) phi[t] = std::pow(X, terms[t].p) * std::pow(Y, terms[t].q);
    for (size_t r = 0; r < nt; ++r) {
      for (size_t c = 0; c < nt; ++c) n[r][c] += phi[r] * phi[c];
      n[r][nt] += phi[r] * p[2];
    }
  }
  for (size_t col = 0; col < nt; ++col) {  // Gauss-Jordan with partial pivoting
    size_t piv = col;
    for (size_t r = col + 1; r < nt; ++r) {
      if (std::fabs(n[r][col]) > std::fabs(n[piv][col])) piv = r;
    }
    std::swap(n[col], n[piv]);
    for (size_t r = 0; r < nt; ++r) {
      if (r == col) continue;
      const long double f = n[r][col] / n[col][col];
      for (size_t c = col; c <= nt; ++c) n[r][c] -= f * n[col][c];
    }
  }
  long double norm_coeff[kSurfaceXDegree + 1][kSurfaceYDegree + 1] = {};
  for (size_t t = 0; t < nt; ++t) norm_coeff[terms[t].p][terms[t].q] = n[t][nt] / n[t][t];
  auto binom = [](int a, int b) {
    long double r = 1;
    for (int i = 1; i <= b; ++i) r = r * (a - b + i) / i;
    return r;
  };
  for (int p = 0; p <= kSurfaceXDegree; ++p) {  // raw coefficient of x^p y^q
    for (int q = 0; q <= kSurfaceYDegree; ++q) {
      long double sum = 0;
      for (int m = p; m <= kSurfaceXDegree; ++m) {
        for (int r = q; r <= kSurfaceYDegree; ++r) {
          sum += norm_coeff[m][r] * binom(m, p) * std::pow(-cx, m - p) / std::pow(hx, m) *
                 binom(r, q) * std::pow(-cy, r - q) / std::pow(hy, r);
        }
      }
      s.coeff_xy[p][q] = static_cast<double>(sum);
    }
  }
  return s;
}

/// Every term x^p y^q, p <= 3, q <= 5: the firmware surface's full form.
inline std::vector<XyPowers> FullSurfaceTerms() {
  std::vector<XyPowers> terms;
  for (int p = 0; p <= kSurfaceXDegree; ++p) {
    for (int q = 0; q <= kSurfaceYDegree; ++q) terms.push_back({p, q});
  }
  return terms;
}

/// ADS constants fitted by least squares on ISA data over the envelope.
inline AdsCalibrationConstants RealisticAds() {
  std::vector<std::array<double, 3>> alt, cas;
  for (double temp_c = -40.0; temp_c <= 85.0; temp_c += 12.5) {
    for (double alt_ft = -1000.0; alt_ft <= 50000.0; alt_ft += 1000.0) {
      alt.push_back({PressureCode(IsaPressure_pa(alt_ft), temp_c), BridgeCode(temp_c), alt_ft});
    }
    for (double cas_kt = 30.0; cas_kt <= 450.0; cas_kt += 10.0) {
      cas.push_back({PressureCode(ImpactPressure_pa(cas_kt), temp_c), BridgeCode(temp_c), cas_kt});
    }
  }
  return AdsCalibrationConstants{FitSurface(alt), FitSurface(cas)};
}

/// The same bridges calibrated for the firmware's laws: surfaces of static and impact pressure
/// (Pa), in the full degree-(3, 5) form, so every coefficient word of the blocks is exercised. Each
/// surface in the bridge code's linearisation (so every block word, the linearisation's too, is
/// exercised).
inline AdsCalibrationConstants RealisticPressureAds() {
  std::vector<std::array<double, 3>> ps, qc;
  const BridgeLinearisation static_linearisation = BridgeCodeLinearisation(1.0);
  const BridgeLinearisation pitot_linearisation = BridgeCodeLinearisation(1.01);
  for (double temp_c = -40.0; temp_c <= 85.0; temp_c += 12.5) {
    const double s_static = LinearisedBridgeCode(static_linearisation, BridgeCode(temp_c));
    const double s_pitot = LinearisedBridgeCode(pitot_linearisation, 1.01 * BridgeCode(temp_c));
    for (double alt_ft = -1000.0; alt_ft <= 50000.0; alt_ft += 1000.0) {
      ps.push_back(
          {PressureCode(IsaPressure_pa(alt_ft), temp_c), s_static, IsaPressure_pa(alt_ft)});
    }
    for (double cas_kt = 30.0; cas_kt <= 450.0; cas_kt += 10.0) {
      qc.push_back(
          {PressureCode(ImpactPressure_pa(cas_kt), temp_c), s_pitot, ImpactPressure_pa(cas_kt)});
    }
  }
  AdsCalibrationConstants c{FitSurface(ps, FullSurfaceTerms()), FitSurface(qc, FullSurfaceTerms())};
  c.altitude_ft.y_linearisation = static_linearisation;
  c.airspeed_kt.y_linearisation = pitot_linearisation;
  c.altitude_ft.law = SurfaceLaw::kIsaAltitude;
  c.airspeed_kt.law = SurfaceLaw::kCas;
  // Hysteresis terms of the model-1230 class's magnitude (physics.md section 6: half loops of
  // 0.05 % and 0.075 % FSO of a 15 psi and a 5 psi bridge, following a -2,500 ppm/degC span
  // tempco, spans 20 % FS and 20 degC), the die temperature the inverse of BridgeCode above.
  constexpr double kCodePerDegC = 6710886.0 * 0.0026;
  c.altitude_ft.hysteresis = {-51.7,
                              51.7 * 0.0025,
                              20684.0,
                              -77.6,
                              77.6 * 0.0025,
                              20.0,
                              6710886.0,
                              {25.0, 1.0 / kCodePerDegC, 0.0, 0.0}};
  c.airspeed_kt.hysteresis = {-17.2,
                              17.2 * 0.0025,
                              6895.0,
                              -25.9,
                              25.9 * 0.0025,
                              20.0,
                              6710886.0 * 1.01,
                              {25.0, 1.0 / (kCodePerDegC * 1.01), 0.0, 0.0}};
  return c;
}

inline AdsRawFrame SynthesiseAds(double alt_ft, double cas_kt, double temp_c) {
  AdsRawFrame raw{};
  raw.ps_cnt = static_cast<int32_t>(std::lround(PressureCode(IsaPressure_pa(alt_ft), temp_c)));
  raw.pt_cnt = static_cast<int32_t>(std::lround(PressureCode(ImpactPressure_pa(cas_kt), temp_c)));
  raw.ps_bridge_cnt = static_cast<int32_t>(std::lround(BridgeCode(temp_c)));
  raw.pt_bridge_cnt = static_cast<int32_t>(std::lround(BridgeCode(temp_c) * 1.01));
  raw.oat_cnt = 0;
  return raw;
}

}  // namespace adahrs::firmware_model::testing
