// The calibration pipeline's double-precision constants for one IM3 and one ADS unit, in the raw
// units of the reference method (reference-method.md steps 2-6), with a JSON round trip. The
// calibration solvers produce these; constants_exporter.h turns them into target blocks.
// IMU, per channel (az1 ax1 ay1 az2 ax2 ay2 gx gy gz, imu_constants.h): thermal cubic xi(t) over
// [temp_min_cnt, temp_max_cnt] (Eq. 4-5 extended; the reference's quadratic has k[3] = 0),
// accelerometer offset and scale (Eq. 12), gyro null and cubic (Eq. 23), cross-axis CA and CG
// (Eq. 26, 29), and optionally the format-3 scale-temperature terms. ADS, per output: a surface
// z = sum_{p<=3, q<=5} coeff_xy[p][q] x^p y^q in the pressure and bridge-voltage codes with its
// code box, the reference's 10-term cubic as the instance with every other term zero
// (ReferenceCubicTerm), plus law, hysteresis and linearisation options.
// Units: raw units (duty, counts, codes), Ca in g, A in m/s^2, rates in deg/s, ft, kt, Pa.
// Every field, its unit and its JSON key: docs/constants-file.md; the stages that apply them:
// docs/firmware-compensator.md ("Stages").
// Left out: uncertainty of the constants, fit residual statistics (the solvers report those).
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

namespace adahrs::firmware_model {

struct ThermalFit {
  int temp_sensor = 0;            ///< 0..2
  std::array<double, 4> k = {};   ///< U units per count^i
  double temp_min_cnt = 0.0;      ///< lowest temperature count the fit covers
  double temp_max_cnt = 65535.0;  ///< highest temperature count the fit covers
};

struct AccelScaleFit {
  double offset_duty = 0.0;
  double scale_duty_per_g = 0.04;
};

struct GyroCubicFit {
  double null_cnt = 0.0;
  std::array<double, 4> l = {};  ///< deg/s per count^i
};

/// One temperature sensor's count span for the scale factors: the polynomials' origin (a whole
/// count) and the span they were fitted over (the exporter normalises to it).
struct TempSensorSpan {
  double origin_cnt = 32768.0;
  double min_cnt = 0.0;
  double max_cnt = 65535.0;
};

/// Constants format 3 (target/imu_constants.h "Scale-temperature stages"). Inactive: a format-2
/// unit, and the JSON form has no "scale_temperature".
struct ImuScaleTemperature {
  bool active = false;
  std::array<TempSensorSpan, 3> sensor;
  /// Per channel F(t) = sum_j scale[j] (t - origin)^j, dimensionless per count^j; F = 1 is
  /// {1, 0, 0, 0}.
  std::array<std::array<double, 4>, 9> scale = {};
  std::array<double, 3> accel_quadratic_per_g = {};  ///< q of body x, y, z, g per g^2
  std::array<std::array<double, 3>, 3> gs_dps_per_mps2 = {};
};

struct ImuCalibrationConstants {
  std::array<ThermalFit, 9> thermal;
  std::array<AccelScaleFit, 6> accel;
  std::array<GyroCubicFit, 3> gyro;
  std::array<std::array<double, 3>, 3> ca_mps2_per_g = {};
  std::array<std::array<double, 3>, 3> cg = {};
  ImuScaleTemperature scale_temperature;
};

/// What follows an ADS surface (target/air_data_law.h): nothing, the surface's z being altitude in
/// ft or airspeed in kt; or the ISA altitude / CAS law, z being static / impact pressure in Pa.
enum class SurfaceLaw { kDirect, kIsaAltitude, kCas };

inline constexpr int kSurfaceXDegree = 3;
inline constexpr int kSurfaceYDegree = 5;
/// [p][q]: the coefficient of x^p y^q, in z units per count^(p+q).
using SurfaceCoefficients =
    std::array<std::array<double, kSurfaceYDegree + 1>, kSurfaceXDegree + 1>;

/// The powers (p of x, q of y) of the reference cubic's letter `t` (a = 0 .. j = 9).
struct XyPowers {
  int p;
  int q;
};
inline constexpr XyPowers kReferenceCubicTerm[10] = {
    {0, 0}, {1, 0}, {0, 1}, {2, 0}, {0, 2}, {1, 1}, {3, 0}, {0, 3}, {1, 2}, {2, 1}};

/// The branch terms the unit adds to a surface's z (target/ads_constants.h HysteresisTermQ):
/// z + gain_P(T) s_P + gain_T(T) s_T, gain(T) = gain + gain_per_c (T -
/// kHysteresisGainReferenceC), each state from a Preisach operator: the pressure one driven by z,
/// the thermal one by the die temperature T(y) = sum_j die_temp_c[j] (y - die_temp_origin_code)^j
/// of the surface's y (the bridge-voltage code, or its linearised code), which also gives the
/// gains' T. A span of 0 switches its operator off (its gains must then be 0). Absent from a
/// constants file: both off, the static surface.
inline constexpr double kHysteresisGainReferenceC = 25.0;

struct HysteresisCompensation {
  double pressure_gain = 0.0;        ///< z units per unit state at 25 degC
  double pressure_gain_per_c = 0.0;  ///< its change per degC of die temperature
  double pressure_span = 0.0;        ///< z travel after a reversal to the full state
  double thermal_gain = 0.0;         ///< z units per unit state at 25 degC
  double thermal_gain_per_c = 0.0;
  double thermal_span_c = 0.0;  ///< die-temperature travel to the full state, degC
  double die_temp_origin_code = 0.0;
  std::array<double, 4> die_temp_c = {};  ///< degC per code^j
  bool active() const { return pressure_span != 0.0 || thermal_span_c != 0.0; }
};

/// The bridge-voltage code's linearisation in die temperature (target/bridge_linearisation.h):
/// with kappa = curvature_per_code != 0 the surface's y is the linearised code
///   s(y) = origin + 2 (y - origin) / (1 + sqrt(1 + kappa (y - origin))),
/// which is origin + b dT where y = origin + b dT + (kappa b^2 / 4) dT^2. kappa = 0: y itself.
/// The origin is a whole code (the target holds it as one). Absent from a constants file: off.
struct BridgeLinearisation {
  double origin_code = 0.0;
  double curvature_per_code = 0.0;  ///< kappa, 1/code
  bool active() const { return curvature_per_code != 0.0; }
};

/// A surface z(x, y) in pressure code x and bridge-voltage code y (the linearised code when
/// y_linearisation is active: the y box and the coefficients are then in s).
struct SurfaceFit {
  SurfaceCoefficients coeff_xy = {};
  double x_min_code = 0.0;
  double x_max_code = 0.0;
  double y_min_code = 0.0;
  double y_max_code = 0.0;
  SurfaceLaw law = SurfaceLaw::kDirect;
  HysteresisCompensation hysteresis;
  BridgeLinearisation y_linearisation;
};

struct AdsCalibrationConstants {
  SurfaceFit altitude_ft;
  SurfaceFit airspeed_kt;
};

/// JSON forms; the readers throw std::runtime_error naming the JSON path of a missing, mistyped
/// or unexpected key, from `root` (the object's own path in the document read, e.g.
/// "$.constants" in a constants file).
nlohmann::json ToJson(const ImuCalibrationConstants& constants);
nlohmann::json ToJson(const AdsCalibrationConstants& constants);
ImuCalibrationConstants ImuCalibrationConstantsFromJson(const nlohmann::json& json,
                                                        const std::string& root = "imu");
AdsCalibrationConstants AdsCalibrationConstantsFromJson(const nlohmann::json& json,
                                                        const std::string& root = "ads");

/// `ads` (an ADS constants object, or its standard errors, which have its shape) with the keys that
/// files of earlier software spell otherwise under today's names: a hysteresis object's
/// `pressure_gain_per_c` and `thermal_gain_per_c` become `pressure_gain_per_c` and
/// `thermal_gain_per_c`. A key present under both names is refused (std::runtime_error naming its
/// JSON path); anything that is not such an object is returned unchanged for the reader to refuse.
/// AdsCalibrationConstantsFromJson applies it.
nlohmann::json WithCurrentAdsKeys(nlohmann::json ads, const std::string& root = "ads");

}  // namespace adahrs::firmware_model
