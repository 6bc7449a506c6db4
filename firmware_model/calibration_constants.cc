#include "firmware_model/calibration_constants.h"

#include <cmath>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace adahrs::firmware_model {
namespace {

using nlohmann::json;

// Reads object `j` at `path`: every key must be in `keys` or `optional`, and every key in `keys`
// present.
void ExpectKeys(const json& j,
                const std::string& path,
                const std::set<std::string>& keys,
                const std::set<std::string>& optional = {}) {
  if (!j.is_object()) throw std::runtime_error(path + ": expected an object");
  for (const auto& [key, value] : j.items()) {
    if (!keys.count(key) && !optional.count(key))
      throw std::runtime_error(path + "." + key + ": unexpected key");
  }
  for (const std::string& key : keys) {
    if (!j.contains(key)) throw std::runtime_error(path + "." + key + ": missing");
  }
}

double Number(const json& j, const std::string& path) {
  if (!j.is_number()) throw std::runtime_error(path + ": expected a number");
  return j.get<double>();
}

template <size_t N>
std::array<double, N> Numbers(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != N) {
    throw std::runtime_error(path + ": expected an array of " + std::to_string(N) + " numbers");
  }
  std::array<double, N> out{};
  for (size_t i = 0; i < N; ++i) out[i] = Number(j[i], path + "[" + std::to_string(i) + "]");
  return out;
}

std::array<std::array<double, 3>, 3> Matrix(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error(path + ": expected 3 rows");
  std::array<std::array<double, 3>, 3> m{};
  for (size_t r = 0; r < 3; ++r) m[r] = Numbers<3>(j[r], path + "[" + std::to_string(r) + "]");
  return m;
}

const json& Array(const json& j, const std::string& path, size_t n) {
  if (!j.is_array() || j.size() != n) {
    throw std::runtime_error(path + ": expected an array of " + std::to_string(n));
  }
  return j;
}

constexpr std::pair<SurfaceLaw, const char*> kLawNames[] = {
    {SurfaceLaw::kDirect, "direct"},
    {SurfaceLaw::kIsaAltitude, "isa_altitude"},
    {SurfaceLaw::kCas, "cas"}};

json SurfaceToJson(const SurfaceFit& s) {
  const char* law = "";
  for (const auto& [value, name] : kLawNames) {
    if (value == s.law) law = name;
  }
  json out{{"coeff_x_y", s.coeff_xy},
           {"x_min_code", s.x_min_code},
           {"x_max_code", s.x_max_code},
           {"y_min_code", s.y_min_code},
           {"y_max_code", s.y_max_code},
           {"law", law}};
  if (s.hysteresis.active()) {
    const HysteresisCompensation& h = s.hysteresis;
    out["hysteresis"] = {{"pressure_gain", h.pressure_gain},
                         {"pressure_gain_per_c", h.pressure_gain_per_c},
                         {"pressure_span", h.pressure_span},
                         {"thermal_gain", h.thermal_gain},
                         {"thermal_gain_per_c", h.thermal_gain_per_c},
                         {"thermal_span_c", h.thermal_span_c},
                         {"die_temp_origin_code", h.die_temp_origin_code},
                         {"die_temp_c", h.die_temp_c}};
  }
  if (s.y_linearisation.active()) {
    out["y_linearisation"] = {{"origin_code", s.y_linearisation.origin_code},
                              {"curvature_per_code", s.y_linearisation.curvature_per_code}};
  }
  return out;
}

// "y_linearisation": a whole origin code and a finite curvature.
BridgeLinearisation LinearisationFromJson(const json& j, const std::string& path) {
  ExpectKeys(j, path, {"origin_code", "curvature_per_code"});
  BridgeLinearisation l;
  l.origin_code = Number(j["origin_code"], path + ".origin_code");
  l.curvature_per_code = Number(j["curvature_per_code"], path + ".curvature_per_code");
  if (l.origin_code != std::nearbyint(l.origin_code)) {
    throw std::runtime_error(path + ".origin_code: must be a whole code");
  }
  return l;
}

// "hysteresis": both operators' gains and spans and the die temperature of the bridge code. A
// zero span with a non-zero gain is refused (the state would never move, so the gain would be a
// constant offset in disguise), as are negative spans and a thermal span without a temperature.
HysteresisCompensation HysteresisFromJson(const json& j, const std::string& path) {
  ExpectKeys(j,
             path,
             {"pressure_gain",
              "pressure_gain_per_c",
              "pressure_span",
              "thermal_gain",
              "thermal_gain_per_c",
              "thermal_span_c",
              "die_temp_origin_code",
              "die_temp_c"});
  HysteresisCompensation h;
  h.pressure_gain = Number(j["pressure_gain"], path + ".pressure_gain");
  h.pressure_gain_per_c = Number(j["pressure_gain_per_c"], path + ".pressure_gain_per_c");
  h.pressure_span = Number(j["pressure_span"], path + ".pressure_span");
  h.thermal_gain = Number(j["thermal_gain"], path + ".thermal_gain");
  h.thermal_gain_per_c = Number(j["thermal_gain_per_c"], path + ".thermal_gain_per_c");
  h.thermal_span_c = Number(j["thermal_span_c"], path + ".thermal_span_c");
  h.die_temp_origin_code = Number(j["die_temp_origin_code"], path + ".die_temp_origin_code");
  h.die_temp_c = Numbers<4>(j["die_temp_c"], path + ".die_temp_c");
  for (const auto& [span, gain, slope, name] :
       {std::tuple{h.pressure_span, h.pressure_gain, h.pressure_gain_per_c, "pressure"},
        std::tuple{h.thermal_span_c, h.thermal_gain, h.thermal_gain_per_c, "thermal"}}) {
    if (span < 0.0) throw std::runtime_error(path + "." + name + " span: must not be negative");
    if (span == 0.0 && (gain != 0.0 || slope != 0.0)) {
      throw std::runtime_error(path + "." + name + "_gain: non-zero with a zero span");
    }
  }
  const bool needs_temperature =
      h.thermal_span_c != 0.0 || h.pressure_gain_per_c != 0.0 || h.thermal_gain_per_c != 0.0;
  if (needs_temperature && h.die_temp_c[1] == 0.0 && h.die_temp_c[2] == 0.0 &&
      h.die_temp_c[3] == 0.0) {
    throw std::runtime_error(path +
                             ".die_temp_c: no temperature dependence, but a thermal span or "
                             "a gain's temperature slope needs one");
  }
  return h;
}

// The coefficients: "coeff_x_y" (rows p = 0..3 of x, columns q = 0..5 of y), or, in files written
// before the surface grew beyond the reference cubic, "coeff_a_to_j" in the reference's letters.
SurfaceCoefficients CoefficientsFromJson(const json& j, const std::string& path) {
  const bool xy = j.contains("coeff_x_y"), letters = j.contains("coeff_a_to_j");
  if (xy == letters) {
    throw std::runtime_error(path + ": expected exactly one of coeff_x_y and coeff_a_to_j");
  }
  SurfaceCoefficients c{};
  if (letters) {
    const auto a_to_j = Numbers<10>(j["coeff_a_to_j"], path + ".coeff_a_to_j");
    for (int t = 0; t < 10; ++t) c[kReferenceCubicTerm[t].p][kReferenceCubicTerm[t].q] = a_to_j[t];
    return c;
  }
  const std::string rows = path + ".coeff_x_y";
  Array(j["coeff_x_y"], rows, kSurfaceXDegree + 1);
  for (int p = 0; p <= kSurfaceXDegree; ++p) {
    c[p] = Numbers<kSurfaceYDegree + 1>(j["coeff_x_y"][p], rows + "[" + std::to_string(p) + "]");
  }
  return c;
}

// `pressure_law` the one law this surface may carry besides "direct"; a surface without "law"
// (files written before it existed) is direct.
SurfaceFit SurfaceFromJson(const json& j, const std::string& path, SurfaceLaw pressure_law) {
  ExpectKeys(j,
             path,
             {"x_min_code", "x_max_code", "y_min_code", "y_max_code"},
             {"law", "coeff_x_y", "coeff_a_to_j", "hysteresis", "y_linearisation"});
  SurfaceFit s;
  if (j.contains("law")) {
    const std::string allowed = pressure_law == SurfaceLaw::kIsaAltitude ? "isa_altitude" : "cas";
    if (!j["law"].is_string() || (j["law"] != "direct" && j["law"] != allowed)) {
      throw std::runtime_error(path + ".law: expected \"direct\" or \"" + allowed + "\"");
    }
    s.law = j["law"] == "direct" ? SurfaceLaw::kDirect : pressure_law;
  }
  s.coeff_xy = CoefficientsFromJson(j, path);
  if (j.contains("hysteresis"))
    s.hysteresis = HysteresisFromJson(j["hysteresis"], path + ".hysteresis");
  if (j.contains("y_linearisation")) {
    s.y_linearisation = LinearisationFromJson(j["y_linearisation"], path + ".y_linearisation");
  }
  s.x_min_code = Number(j["x_min_code"], path + ".x_min_code");
  s.x_max_code = Number(j["x_max_code"], path + ".x_max_code");
  s.y_min_code = Number(j["y_min_code"], path + ".y_min_code");
  s.y_max_code = Number(j["y_max_code"], path + ".y_max_code");
  if (!(s.x_min_code < s.x_max_code) || !(s.y_min_code < s.y_max_code)) {
    throw std::runtime_error(path + ": empty code box");
  }
  return s;
}

json ScaleTemperatureToJson(const ImuScaleTemperature& st) {
  json sensors = json::array();
  for (const TempSensorSpan& span : st.sensor) {
    sensors.push_back(
        {{"origin_cnt", span.origin_cnt}, {"min_cnt", span.min_cnt}, {"max_cnt", span.max_cnt}});
  }
  return json{{"sensor", sensors},
              {"scale", st.scale},
              {"accel_quadratic_per_g", st.accel_quadratic_per_g},
              {"gs_dps_per_mps2", st.gs_dps_per_mps2}};
}

// "scale_temperature": spans with a whole origin inside an increasing span in 0..65535.
ImuScaleTemperature ScaleTemperatureFromJson(const json& j, const std::string& path) {
  ExpectKeys(j, path, {"sensor", "scale", "accel_quadratic_per_g", "gs_dps_per_mps2"});
  ImuScaleTemperature st;
  st.active = true;
  const json& sensors = Array(j["sensor"], path + ".sensor", 3);
  for (size_t s = 0; s < 3; ++s) {
    const std::string sp = path + ".sensor[" + std::to_string(s) + "]";
    ExpectKeys(sensors[s], sp, {"origin_cnt", "min_cnt", "max_cnt"});
    TempSensorSpan& span = st.sensor[s];
    span.origin_cnt = Number(sensors[s]["origin_cnt"], sp + ".origin_cnt");
    span.min_cnt = Number(sensors[s]["min_cnt"], sp + ".min_cnt");
    span.max_cnt = Number(sensors[s]["max_cnt"], sp + ".max_cnt");
    if (span.origin_cnt != std::nearbyint(span.origin_cnt)) {
      throw std::runtime_error(sp + ".origin_cnt: must be a whole count");
    }
    if (!(span.min_cnt >= 0.0 && span.min_cnt <= span.origin_cnt &&
          span.origin_cnt <= span.max_cnt && span.min_cnt < span.max_cnt &&
          span.max_cnt <= 65535.0)) {
      throw std::runtime_error(sp +
                               ": min_cnt <= origin_cnt <= max_cnt must be an increasing span "
                               "inside 0..65535");
    }
  }
  const json& scale = Array(j["scale"], path + ".scale", 9);
  for (size_t c = 0; c < 9; ++c) {
    st.scale[c] = Numbers<4>(scale[c], path + ".scale[" + std::to_string(c) + "]");
  }
  st.accel_quadratic_per_g =
      Numbers<3>(j["accel_quadratic_per_g"], path + ".accel_quadratic_per_g");
  st.gs_dps_per_mps2 = Matrix(j["gs_dps_per_mps2"], path + ".gs_dps_per_mps2");
  return st;
}

}  // namespace

json ToJson(const ImuCalibrationConstants& c) {
  json thermal = json::array();
  for (const ThermalFit& t : c.thermal) {
    thermal.push_back({{"temp_sensor", t.temp_sensor},
                       {"k", t.k},
                       {"temp_min_cnt", t.temp_min_cnt},
                       {"temp_max_cnt", t.temp_max_cnt}});
  }
  json accel = json::array();
  for (const AccelScaleFit& a : c.accel) {
    accel.push_back({{"offset_duty", a.offset_duty}, {"scale_duty_per_g", a.scale_duty_per_g}});
  }
  json gyro = json::array();
  for (const GyroCubicFit& g : c.gyro) gyro.push_back({{"null_cnt", g.null_cnt}, {"l", g.l}});
  json out{{"thermal", thermal},
           {"accel", accel},
           {"gyro", gyro},
           {"ca_mps2_per_g", c.ca_mps2_per_g},
           {"cg", c.cg}};
  if (c.scale_temperature.active)
    out["scale_temperature"] = ScaleTemperatureToJson(c.scale_temperature);
  return out;
}

ImuCalibrationConstants ImuCalibrationConstantsFromJson(const json& j, const std::string& root) {
  ExpectKeys(j, root, {"thermal", "accel", "gyro", "ca_mps2_per_g", "cg"}, {"scale_temperature"});
  ImuCalibrationConstants c;
  const json& thermal = Array(j["thermal"], root + ".thermal", 9);
  for (size_t i = 0; i < 9; ++i) {
    const std::string path = root + ".thermal[" + std::to_string(i) + "]";
    ExpectKeys(thermal[i], path, {"temp_sensor", "k", "temp_min_cnt", "temp_max_cnt"});
    const double sensor = Number(thermal[i]["temp_sensor"], path + ".temp_sensor");
    if (sensor != 0.0 && sensor != 1.0 && sensor != 2.0) {
      throw std::runtime_error(path + ".temp_sensor: must be 0, 1 or 2, got " +
                               std::to_string(sensor));
    }
    c.thermal[i].temp_sensor = static_cast<int>(sensor);
    c.thermal[i].k = Numbers<4>(thermal[i]["k"], path + ".k");
    c.thermal[i].temp_min_cnt = Number(thermal[i]["temp_min_cnt"], path + ".temp_min_cnt");
    c.thermal[i].temp_max_cnt = Number(thermal[i]["temp_max_cnt"], path + ".temp_max_cnt");
    if (!(c.thermal[i].temp_min_cnt >= 0.0 &&
          c.thermal[i].temp_min_cnt < c.thermal[i].temp_max_cnt &&
          c.thermal[i].temp_max_cnt <= 65535.0)) {
      throw std::runtime_error(path + ": temp_min_cnt " +
                               std::to_string(c.thermal[i].temp_min_cnt) + " .. temp_max_cnt " +
                               std::to_string(c.thermal[i].temp_max_cnt) +
                               " must be an increasing span inside 0..65535");
    }
  }
  const json& accel = Array(j["accel"], root + ".accel", 6);
  for (size_t i = 0; i < 6; ++i) {
    const std::string path = root + ".accel[" + std::to_string(i) + "]";
    ExpectKeys(accel[i], path, {"offset_duty", "scale_duty_per_g"});
    c.accel[i].offset_duty = Number(accel[i]["offset_duty"], path + ".offset_duty");
    c.accel[i].scale_duty_per_g = Number(accel[i]["scale_duty_per_g"], path + ".scale_duty_per_g");
    if (c.accel[i].scale_duty_per_g == 0.0) {
      throw std::runtime_error(path + ".scale_duty_per_g: must not be zero");
    }
  }
  const json& gyro = Array(j["gyro"], root + ".gyro", 3);
  for (size_t i = 0; i < 3; ++i) {
    const std::string path = root + ".gyro[" + std::to_string(i) + "]";
    ExpectKeys(gyro[i], path, {"null_cnt", "l"});
    c.gyro[i].null_cnt = Number(gyro[i]["null_cnt"], path + ".null_cnt");
    c.gyro[i].l = Numbers<4>(gyro[i]["l"], path + ".l");
  }
  c.ca_mps2_per_g = Matrix(j["ca_mps2_per_g"], root + ".ca_mps2_per_g");
  c.cg = Matrix(j["cg"], root + ".cg");
  if (j.contains("scale_temperature")) {
    c.scale_temperature =
        ScaleTemperatureFromJson(j["scale_temperature"], root + ".scale_temperature");
  }
  return c;
}

json ToJson(const AdsCalibrationConstants& c) {
  return json{{"altitude_ft", SurfaceToJson(c.altitude_ft)},
              {"airspeed_kt", SurfaceToJson(c.airspeed_kt)}};
}

json WithCurrentAdsKeys(json ads, const std::string& root) {
  if (!ads.is_object()) return ads;
  for (const char* surface : {"altitude_ft", "airspeed_kt"}) {
    if (!ads.contains(surface) || !ads[surface].is_object() ||
        !ads[surface].contains("hysteresis") || !ads[surface]["hysteresis"].is_object()) {
      continue;
    }
    json& h = ads[surface]["hysteresis"];
    for (const auto& [old_key, key] : {std::pair{"pressure_gain_per_degc", "pressure_gain_per_c"},
                                       std::pair{"thermal_gain_per_degc", "thermal_gain_per_c"}}) {
      if (!h.contains(old_key)) continue;
      if (h.contains(key)) {
        throw std::runtime_error(root + "." + surface + ".hysteresis." + old_key +
                                 ": the same as " + key + ", which is present too");
      }
      h[key] = std::move(h[old_key]);
      h.erase(old_key);
    }
  }
  return ads;
}

AdsCalibrationConstants AdsCalibrationConstantsFromJson(const json& file_json,
                                                        const std::string& root) {
  const json j = WithCurrentAdsKeys(file_json, root);
  ExpectKeys(j, root, {"altitude_ft", "airspeed_kt"});
  AdsCalibrationConstants c;
  c.altitude_ft =
      SurfaceFromJson(j["altitude_ft"], root + ".altitude_ft", SurfaceLaw::kIsaAltitude);
  c.airspeed_kt = SurfaceFromJson(j["airspeed_kt"], root + ".airspeed_kt", SurfaceLaw::kCas);
  return c;
}

}  // namespace adahrs::firmware_model
