#include "firmware_model/reference_compensator.h"

#include <cmath>

#include "firmware_model/air_data_law.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {
namespace {

constexpr int kPairOfAxis[3][2] = {{1, 4}, {2, 5}, {0, 3}};  // x, y, z: (ch1, ch2)

double Scale(int8_t exponent) { return std::ldexp(1.0, exponent - 31); }

// F(t) of one channel (calibration_constants.h ImuScaleTemperature).
double ScaleFactor(const ImuScaleTemperature& st,
                   int sensor,
                   const std::array<double, 4>& f,
                   double temp_cnt) {
  const double d = temp_cnt - st.sensor[sensor].origin_cnt;
  return f[0] + d * (f[1] + d * (f[2] + d * f[3]));
}

}  // namespace

double ThermalDrift(const ThermalFit& f, double temp_cnt) {
  return f.k[0] + temp_cnt * (f.k[1] + temp_cnt * (f.k[2] + temp_cnt * f.k[3]));
}

double ScaleTemperatureFactor(const ImuCalibrationConstants& c,
                              int channel,
                              const ImuRawFrame& raw) {
  const ImuScaleTemperature& st = c.scale_temperature;
  if (!st.active) return 1.0;
  const int sensor = c.thermal[channel].temp_sensor;
  return ScaleFactor(st, sensor, st.scale[channel], raw.temp_cnt[sensor]);
}

double GyroCubic(const ImuCalibrationConstants& c, int axis, double d) {
  const auto& l = c.gyro[axis].l;
  return l[0] + l[1] * d + l[2] * d * d + l[3] * d * d * d;
}

std::array<double, 9> ImuReference(const ImuCalibrationConstants& c,
                                   ImuCompensationMode mode,
                                   const ImuRawFrame& raw) {
  std::array<double, 9> u{};
  for (int i = 0; i < 6; ++i) {
    u[i] = static_cast<double>(raw.t1_cnt[i]) / static_cast<double>(raw.t2_cnt[i]) - 0.5;
  }
  for (int g = 0; g < 3; ++g) u[6 + g] = static_cast<double>(raw.gyro_cnt[g]);
  if (mode == ImuCompensationMode::kRaw) return u;

  std::array<double, 9> t{};
  for (int i = 0; i < 9; ++i) {
    t[i] = u[i] - ThermalDrift(c.thermal[i], raw.temp_cnt[c.thermal[i].temp_sensor]);
  }
  if (mode == ImuCompensationMode::kThermal) return t;

  // Format 3: F scales each channel's sensed input, so an accelerometer's linear value is scaled
  // and a gyro's count before its cubic (the cubic then inverts a temperature-free response).
  const ImuScaleTemperature& st = c.scale_temperature;
  std::array<double, 9> factor{};
  for (int i = 0; i < 9; ++i) factor[i] = ScaleTemperatureFactor(c, i, raw);
  std::array<double, 9> cal{};
  for (int i = 0; i < 6; ++i) {
    cal[i] = (t[i] - c.accel[i].offset_duty) / c.accel[i].scale_duty_per_g * factor[i];
  }
  for (int g = 0; g < 3; ++g) {
    cal[6 + g] = GyroCubic(c, g, (t[6 + g] - c.gyro[g].null_cnt) * factor[6 + g]);
  }
  if (mode == ImuCompensationMode::kSensorCalibrated) return cal;

  std::array<double, 9> out{};
  std::array<double, 3> ca_g{};
  for (int axis = 0; axis < 3; ++axis) {
    const double ch1 = cal[kPairOfAxis[axis][0]];
    const double ch2 = cal[kPairOfAxis[axis][1]];
    ca_g[axis] = 0.5 * (ch1 + ch2);
    if (st.active) ca_g[axis] += st.accel_quadratic_per_g[axis] * ca_g[axis] * ca_g[axis];
    out[6 + axis] = 0.5 * (ch1 - ch2);
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      out[r] += c.ca_mps2_per_g[r][k] * ca_g[k];
      out[3 + r] += c.cg[r][k] * cal[6 + k];
    }
  }
  if (st.active) {
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) out[3 + r] += st.gs_dps_per_mps2[r][k] * out[k];
    }
  }
  return out;
}

// Horner in y, then in x, in long double: the raw-code monomials of a degree-5 term cancel by up
// to (box centre / half-width)^8 against each other.
double LinearisedBridgeCode(const BridgeLinearisation& l, double y_code) {
  if (!l.active()) return y_code;
  const double dy = y_code - l.origin_code;
  return l.origin_code + 2.0 * dy / (1.0 + std::sqrt(1.0 + l.curvature_per_code * dy));
}

namespace {

double SurfaceAt(const SurfaceFit& s, double x, double y) {
  long double z = 0;
  for (int p = kSurfaceXDegree; p >= 0; --p) {
    long double b = 0;
    for (int q = kSurfaceYDegree; q >= 0; --q) b = b * y + s.coeff_xy[p][q];
    z = z * x + b;
  }
  return static_cast<double>(z);
}

}  // namespace

double EvaluateSurfaceFit(const SurfaceFit& s, double x_code, double y_code) {
  return SurfaceAt(s, x_code, LinearisedBridgeCode(s.y_linearisation, y_code));
}

std::array<double, 2> AdsReference(const AdsCalibrationConstants& c,
                                   AdsCompensationMode mode,
                                   const AdsRawFrame& raw,
                                   const AdsReferenceStates& states) {
  if (mode == AdsCompensationMode::kRaw) {
    return {static_cast<double>(raw.ps_cnt), static_cast<double>(raw.pt_cnt)};
  }
  return {SurfaceOutput(c.altitude_ft,
                        raw.ps_cnt,
                        raw.ps_bridge_cnt,
                        states.static_pressure,
                        states.static_thermal),
          SurfaceOutput(c.airspeed_kt,
                        raw.pt_cnt,
                        raw.pt_bridge_cnt,
                        states.pitot_pressure,
                        states.pitot_thermal)};
}

double SurfaceOutput(
    const SurfaceFit& s, double x_code, double y_code, double s_pressure, double s_thermal) {
  const HysteresisCompensation& h = s.hysteresis;
  const double y = LinearisedBridgeCode(s.y_linearisation, y_code);
  double die_c = 0.0;  // T(y): only the gains' slopes use it
  for (int j = 3; j >= 0; --j) die_c = die_c * (y - h.die_temp_origin_code) + h.die_temp_c[j];
  const double dt_c = die_c - kHysteresisGainReferenceC;
  const double z = SurfaceAt(s, x_code, y) +
                   (h.pressure_gain + h.pressure_gain_per_c * dt_c) * s_pressure +
                   (h.thermal_gain + h.thermal_gain_per_c * dt_c) * s_thermal;
  switch (s.law) {
    case SurfaceLaw::kIsaAltitude:
      return IsaAltitudeFtFromStaticPa(z);
    case SurfaceLaw::kCas:
      return CasKtFromImpactPa(z);
    case SurfaceLaw::kDirect:
      break;
  }
  return z;
}

std::array<double, 9> ImuFrameToDouble(ImuCompensationMode mode, const ImuCompensatedFrame& f) {
  std::array<int8_t, 9> e{};
  switch (mode) {
    case ImuCompensationMode::kRaw:
    case ImuCompensationMode::kThermal:
      e = {0, 0, 0, 0, 0, 0, kGyroCountExponent, kGyroCountExponent, kGyroCountExponent};
      break;
    case ImuCompensationMode::kSensorCalibrated:
      e = {kAccelGExponent,
           kAccelGExponent,
           kAccelGExponent,
           kAccelGExponent,
           kAccelGExponent,
           kAccelGExponent,
           kRateExponent,
           kRateExponent,
           kRateExponent};
      break;
    case ImuCompensationMode::kFullyCalibrated:
      e = {kAccelMps2Exponent,
           kAccelMps2Exponent,
           kAccelMps2Exponent,
           kRateExponent,
           kRateExponent,
           kRateExponent,
           kAccelGExponent,
           kAccelGExponent,
           kAccelGExponent};
      break;
  }
  std::array<double, 9> out{};
  for (int i = 0; i < 9; ++i) out[i] = f.value[i] * Scale(e[i]);
  return out;
}

std::array<double, 2> AdsFrameToDouble(AdsCompensationMode mode, const AdsCompensatedFrame& f) {
  if (mode == AdsCompensationMode::kRaw) return {1.0 * f.value[0], 1.0 * f.value[1]};
  return {f.value[0] * Scale(kAltitudeExponent), f.value[1] * Scale(kAirspeedExponent)};
}

}  // namespace adahrs::firmware_model
