// constants.json (docs/constants-file.md): round trip, and the strict reader refusing each kind of
// bad input with the file and JSON path in the message.
#include "calib/constants/constants_file.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
namespace fm = firmware_model;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ConstantsFile ImuFile() {
  ConstantsFile f;
  f.serial = "IMU-0007";
  f.kind = hil::UnitKind::kImu;
  f.strategy = "reference";
  f.created_utc = "2024-05-01T12:00:00Z";
  f.software_version = "0.1.0";
  fm::ImuCalibrationConstants c;
  fm::ImuCalibrationConstants se;
  for (int i = 0; i < 9; ++i) {
    c.thermal[i] = {i % 3, {0.1 * i, 1e-5 * i, -3e-9 * i}};
    se.thermal[i] = {0, {1e-4, 1e-8, kNaN}};
  }
  for (int i = 0; i < 6; ++i) {
    c.accel[i] = {0.01 * i, (i % 2 ? -1 : 1) * 0.0398};
    se.accel[i] = {2e-6, 3e-7};
  }
  for (int g = 0; g < 3; ++g) {
    c.gyro[g] = {4.19e6 + g, {0.0, 4.77e-5, 1e-13, 1e-20}};
    se.gyro[g] = {3.0, {0.0, 1e-9, 1e-15, 1e-22}};
  }
  c.ca_mps2_per_g = {{{9.8, 0.1, 0.0}, {0.0, 9.81, -0.05}, {0.02, 0.0, 9.79}}};
  c.cg = {{{1.0, 0.01, 0.0}, {0.0, 1.0, 0.0}, {0.0, -0.01, 1.0}}};
  se.ca_mps2_per_g = {{{1e-3, 1e-3, 1e-3}, {1e-3, 1e-3, 1e-3}, {1e-3, 1e-3, 1e-3}}};
  se.cg = {{{1e-4, 1e-4, 1e-4}, {1e-4, 1e-4, 1e-4}, {1e-4, 1e-4, 1e-4}}};
  f.imu = c;
  f.standard_errors = ImuStandardErrorsJson(se);
  f.provenance.recordings = {{"runs/cal1", std::string(64, 'a')}};
  f.provenance.sequence_names = {"imu_sensor_calibration"};
  ImuFitDiagnostics& d = f.imu_diagnostics.emplace();
  d.excluded_rows = 3;
  d.local_gravity_mps2 = 9.80665;
  d.joint.emplace().crb_parameters = {"k0_az1", "k1_az1"};
  d.joint->crb_covariance = {{1e-4, kNaN}, {kNaN, 2e-6}};  // NaN is written null
  return f;
}

// `j` with NaN numbers as null, as the file writes them.
json NullJson(json j) {
  if (j.is_number_float() && std::isnan(j.get<double>())) return nullptr;
  if (j.is_structured()) {
    for (auto& item : j) item = NullJson(item);
  }
  return j;
}

std::string MessageOf(const json& j) {
  try {
    ConstantsFileFromJson(j, "unit.json");
  } catch (const ConstantsFileError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ConstantsFile, RoundTripsThroughDisk) {
  const ConstantsFile f = ImuFile();
  const auto path = std::filesystem::temp_directory_path() / "adahrs_constants_round_trip.json";
  WriteConstantsFile(path, f);
  const ConstantsFile g = ReadConstantsFile(path);
  std::filesystem::remove(path);
  EXPECT_EQ(g.serial, f.serial);
  EXPECT_EQ(g.kind, hil::UnitKind::kImu);
  EXPECT_EQ(g.strategy, "reference");
  EXPECT_EQ(g.provenance, f.provenance);
  ASSERT_TRUE(g.imu.has_value());
  // JSON numbers are written with 17 significant digits by nlohmann: bit-exact round trip.
  EXPECT_EQ(fm::ToJson(*g.imu), fm::ToJson(*f.imu));
  EXPECT_TRUE(g.standard_errors["thermal"][0]["k"][2].is_null());  // NaN = not estimated
  EXPECT_TRUE(g.standard_errors["thermal"][0]["temp_sensor"].is_null());
  EXPECT_DOUBLE_EQ(g.standard_errors["gyro"][1]["l"][1].get<double>(), 1e-9);
  ASSERT_TRUE(g.imu_diagnostics.has_value());
  EXPECT_FALSE(g.ads_diagnostics.has_value());
  EXPECT_EQ(g.imu_diagnostics->excluded_rows, 3);
  EXPECT_EQ(g.imu_diagnostics->local_gravity_mps2, 9.80665);
  ASSERT_TRUE(g.imu_diagnostics->joint.has_value());
  EXPECT_EQ(g.imu_diagnostics->joint->crb_parameters, f.imu_diagnostics->joint->crb_parameters);
  EXPECT_EQ(g.imu_diagnostics->joint->crb_covariance[1][1], 2e-6);
  EXPECT_TRUE(std::isnan(g.imu_diagnostics->joint->crb_covariance[0][1]));
}

// The diagnostics section is read as the kind's typed diagnostics: an unknown key or a wrong type
// is refused with its JSON path, and a section of the other kind's shape is not taken.
TEST(ConstantsFile, DiagnosticsAreReadTypedAndRefusedByPath) {
  json j = ToJson(ImuFile());
  j["diagnostics"]["excluded_rowz"] = 1;
  EXPECT_THAT(MessageOf(j), HasSubstr("unit.json: $.diagnostics.excluded_rowz: unknown key"));
  j = ToJson(ImuFile());
  j["diagnostics"]["local_gravity_mps2"] = "9.8";
  EXPECT_THAT(MessageOf(j),
              HasSubstr("unit.json: $.diagnostics.local_gravity_mps2: expected a number"));
  ConstantsFile f = ImuFile();
  f.ads_diagnostics.emplace();
  EXPECT_THROW(ToJson(f), ConstantsFileError);
}

TEST(ConstantsFile, RefusesWrongFormatAndVersion) {
  json j = ToJson(ImuFile());
  j["format_version"] = 4;
  EXPECT_THAT(MessageOf(j), HasSubstr("unit.json: $.format_version: version 4 is not supported"));
  // Version 1 held a quadratic thermal drift without its temperature span: refit, not guessed.
  j["format_version"] = 1;
  EXPECT_THAT(MessageOf(j), HasSubstr("unit.json: $.format_version: version 1 is not supported"));
  j = ToJson(ImuFile());
  j["format"] = "something-else";
  EXPECT_THAT(MessageOf(j), HasSubstr("$.format"));
}

// Constants with the firmware's format-3 terms are written as version 3 and read back exactly; the
// same constants without them stay version 2; a version-2 file may not carry them.
TEST(ConstantsFile, Format3TermsMakeAVersion3FileAndRoundTrip) {
  ConstantsFile f = ImuFile();
  EXPECT_EQ(ToJson(f)["format_version"], 2);
  EXPECT_FALSE(ToJson(f)["constants"].contains("scale_temperature"));
  fm::ImuScaleTemperature& st = f.imu->scale_temperature;
  st.active = true;
  for (fm::TempSensorSpan& span : st.sensor) span = {32768.0, 27000.0, 40000.0};
  for (int c = 0; c < 9; ++c) st.scale[c] = {1.0 + 1e-4 * c, 2e-7, -1e-11, 3e-16};
  st.accel_quadratic_per_g = {1e-3, -2e-3, 5e-4};
  st.gs_dps_per_mps2 = {{{0.01, 0.0, -0.002}, {0.0, 0.003, 0.0}, {0.001, 0.0, 0.0}}};
  fm::ImuCalibrationConstants se = ImuStandardErrors(ImuFile());
  se.scale_temperature = st;
  for (auto& scale : se.scale_temperature.scale) scale = {1e-5, 1e-9, 1e-13, 1e-17};
  se.scale_temperature.accel_quadratic_per_g = {1e-5, 1e-5, 1e-5};
  se.scale_temperature.gs_dps_per_mps2 = {
      {{1e-4, 1e-4, 1e-4}, {1e-4, 1e-4, 1e-4}, {1e-4, 1e-4, 1e-4}}};
  f.standard_errors = ImuStandardErrorsJson(se);
  const json j = ToJson(f);
  EXPECT_EQ(j["format_version"], 3);
  EXPECT_TRUE(j["standard_errors"]["scale_temperature"]["sensor"][1]["origin_cnt"].is_null());
  const ConstantsFile g = ConstantsFileFromJson(j, "unit.json");
  ASSERT_TRUE(g.imu && g.imu->scale_temperature.active);
  EXPECT_EQ(fm::ToJson(*g.imu), fm::ToJson(*f.imu));
  EXPECT_EQ(ImuStandardErrors(g).scale_temperature.scale[4][2], 1e-13);
  json old = j;
  old["format_version"] = 2;
  EXPECT_THAT(MessageOf(old),
              HasSubstr("unit.json: $.constants.scale_temperature: needs format_version 3"));
  json bad = j;
  bad["constants"]["scale_temperature"]["sensor"][2]["origin_cnt"] = 32768.5;
  bad["standard_errors"]["scale_temperature"]["sensor"][2]["origin_cnt"] = nullptr;
  EXPECT_THAT(
      MessageOf(bad),
      HasSubstr("$.constants.scale_temperature.sensor[2].origin_cnt: must be a whole count"));
}

TEST(ConstantsFile, RefusesMissingAndUnexpectedKeys) {
  json j = ToJson(ImuFile());
  j.erase("strategy");
  EXPECT_THAT(MessageOf(j), HasSubstr("$.strategy: missing key"));
  j = ToJson(ImuFile());
  j["strategy_name"] = "x";
  EXPECT_THAT(MessageOf(j), HasSubstr("strategy_name"));
  j = ToJson(ImuFile());
  j["constants"]["gyro"][1].erase("l");
  EXPECT_THAT(MessageOf(j), HasSubstr("unit.json: $.constants.gyro[1].l: missing"));
}

TEST(ConstantsFile, RefusesStandardErrorsOfAnotherShapeOrSign) {
  json j = ToJson(ImuFile());
  j["standard_errors"]["cg"][2] = {1e-4, 1e-4};
  EXPECT_THAT(MessageOf(j), HasSubstr("$.standard_errors.cg[2]: expected an array of 3"));
  j = ToJson(ImuFile());
  j["standard_errors"]["accel"][4]["offset_duty"] = -1e-6;
  EXPECT_THAT(MessageOf(j),
              HasSubstr("$.standard_errors.accel[4].offset_duty: a standard error must be"));
  j = ToJson(ImuFile());
  j["standard_errors"].erase("ca_mps2_per_g");
  EXPECT_THAT(MessageOf(j), HasSubstr("missing key \"ca_mps2_per_g\""));
}

TEST(ConstantsFile, RefusesABadChecksumAndKind) {
  json j = ToJson(ImuFile());
  j["provenance"]["recordings"][0]["sha256"] = "ABC";
  EXPECT_THAT(MessageOf(j), HasSubstr("$.provenance.recordings[0].sha256: expected 64"));
  j = ToJson(ImuFile());
  j["kind"] = "ads";  // IMU constants under an ADS kind
  EXPECT_THAT(MessageOf(j), HasSubstr("$.constants.accel: unexpected key"));
  j["kind"] = "gps";
  EXPECT_THAT(MessageOf(j), HasSubstr("$.kind: expected \"imu\" or \"ads\""));
}

// Two direct surfaces over one code box, every coefficient set.
fm::AdsCalibrationConstants AdsConstants() {
  fm::AdsCalibrationConstants c;
  c.altitude_ft.x_min_code = -1e6;
  c.altitude_ft.x_max_code = 1e6;
  c.altitude_ft.y_min_code = 2e6;
  c.altitude_ft.y_max_code = 3e6;
  for (int p = 0; p <= fm::kSurfaceXDegree; ++p) {
    for (int q = 0; q <= fm::kSurfaceYDegree; ++q)
      c.altitude_ft.coeff_xy[p][q] = 1.0 + p + 0.25 * q;
  }
  c.airspeed_kt = c.altitude_ft;
  return c;
}

TEST(ConstantsFile, AdsRoundTripAndWriterConsistency) {
  ConstantsFile f;
  f.serial = "ADS-0002";
  f.kind = hil::UnitKind::kAds;
  f.strategy = "reference";
  fm::AdsCalibrationConstants c = AdsConstants();
  c.altitude_ft.y_linearisation = {2500000.0, 7.5e-7};  // the airspeed surface has none
  f.ads = c;
  fm::AdsCalibrationConstants se = c;
  se.altitude_ft.y_linearisation.curvature_per_code = 6e-10;
  f.standard_errors = AdsStandardErrorsJson(se);
  AdsFitDiagnostics& d = f.ads_diagnostics.emplace();
  d.altitude_ft.unit = "pa";
  d.altitude_ft.points = 40;
  d.altitude_ft.residual_rms = 1.25;
  d.altitude_ft.held_out_worst_ratio_by_y_degree = {{2, 0.8}, {3, 0.5}};
  d.altitude_ft.hysteresis_spans.emplace().pressure_span_pa = 2000.0;
  d.airspeed_kt.unit = "kt";
  d.airspeed_kt.y_degree = 2;
  d.airspeed_kt.worst_ratio_at_points = kNaN;  // written null, read back NaN
  d.airspeed_kt.law = "cas_from_qc";
  const ConstantsFile g = ConstantsFileFromJson(ToJson(f), "ads.json");
  ASSERT_TRUE(g.ads_diagnostics.has_value());
  EXPECT_EQ(g.ads_diagnostics->ToJson().dump(), NullJson(d.ToJson()).dump());
  EXPECT_EQ(g.ads_diagnostics->altitude_ft.unit, "pa");
  EXPECT_EQ(g.ads_diagnostics->altitude_ft.held_out_worst_ratio_by_y_degree.at(3), 0.5);
  EXPECT_TRUE(std::isnan(*g.ads_diagnostics->airspeed_kt.worst_ratio_at_points));
  json renamed = ToJson(f);
  renamed["diagnostics"]["airspeed_kt"]["residual_rms_kts"] =
      renamed["diagnostics"]["airspeed_kt"]["residual_rms_kt"];
  EXPECT_THAT(MessageOf(renamed),
              HasSubstr("unit.json: $.diagnostics.airspeed_kt.residual_rms_kts: unknown key"));
  ASSERT_TRUE(g.ads.has_value());
  EXPECT_EQ(g.ads->altitude_ft.coeff_xy, c.altitude_ft.coeff_xy);
  EXPECT_EQ(g.ads->altitude_ft.y_linearisation.origin_code, 2500000.0);
  EXPECT_EQ(g.ads->altitude_ft.y_linearisation.curvature_per_code, 7.5e-7);
  EXPECT_FALSE(g.ads->airspeed_kt.y_linearisation.active());
  EXPECT_FALSE(ToJson(f)["constants"]["airspeed_kt"].contains("y_linearisation"));
  EXPECT_TRUE(g.standard_errors["altitude_ft"]["x_min_code"].is_null());
  EXPECT_TRUE(g.standard_errors["altitude_ft"]["y_linearisation"]["origin_code"].is_null());
  EXPECT_EQ(g.standard_errors["altitude_ft"]["y_linearisation"]["curvature_per_code"], 6e-10);
  // The target holds the origin as a whole code: a fractional one is refused with its path.
  json bad = ToJson(f);
  bad["constants"]["altitude_ft"]["y_linearisation"]["origin_code"] = 2500000.5;
  EXPECT_THAT(MessageOf(bad),
              HasSubstr("altitude_ft.y_linearisation.origin_code: must be a whole code"));
  f.imu = fm::ImuCalibrationConstants{};  // both kinds set: refused by the writer
  EXPECT_THROW(ToJson(f), ConstantsFileError);
}

// Files written before the surface grew beyond the reference cubic carry its ten letters: they are
// read into the same powers of x and y (a = 1, b = x, c = y, ..., j = x^2 y); a surface with both
// forms, or neither, is refused with its JSON path.
TEST(ConstantsFile, ReadsTheReferenceCubicsLettersFromOlderFiles) {
  nlohmann::json surface = {{"coeff_a_to_j", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}},
                            {"x_min_code", -1e6},
                            {"x_max_code", 1e6},
                            {"y_min_code", 2e6},
                            {"y_max_code", 3e6}};
  nlohmann::json ads = {{"altitude_ft", surface}, {"airspeed_kt", surface}};
  const fm::AdsCalibrationConstants c = fm::AdsCalibrationConstantsFromJson(ads);
  const auto& k = c.altitude_ft.coeff_xy;
  EXPECT_EQ(k[0][0], 1);   // a
  EXPECT_EQ(k[1][0], 2);   // b x
  EXPECT_EQ(k[0][1], 3);   // c y
  EXPECT_EQ(k[2][0], 4);   // d x^2
  EXPECT_EQ(k[0][2], 5);   // e y^2
  EXPECT_EQ(k[1][1], 6);   // f x y
  EXPECT_EQ(k[3][0], 7);   // g x^3
  EXPECT_EQ(k[0][3], 8);   // h y^3
  EXPECT_EQ(k[1][2], 9);   // i x y^2
  EXPECT_EQ(k[2][1], 10);  // j x^2 y
  EXPECT_EQ(k[3][5], 0);
  ads["airspeed_kt"]["coeff_x_y"] = fm::ToJson(c)["altitude_ft"]["coeff_x_y"];
  EXPECT_THAT([&] { fm::AdsCalibrationConstantsFromJson(ads); },
              ::testing::ThrowsMessage<std::runtime_error>(
                  HasSubstr("airspeed_kt: expected exactly one of coeff_x_y and coeff_a_to_j")));
  ads["airspeed_kt"].erase("coeff_a_to_j");
  ads["airspeed_kt"]["coeff_x_y"][2] = {1, 2, 3};
  EXPECT_THAT([&] { fm::AdsCalibrationConstantsFromJson(ads); },
              ::testing::ThrowsMessage<std::runtime_error>(
                  HasSubstr("airspeed_kt.coeff_x_y[2]: expected an array of 6 numbers")));
}

// Files of earlier software spell the hysteresis gains' temperature slopes `_per_degc`: read as
// `_per_c` in the constants and in their standard errors, which then have today's shape; a
// hysteresis object with both spellings is refused with its path.
TEST(ConstantsFile, ReadsTheHysteresisSlopesOldSpelling) {
  ConstantsFile f;
  f.serial = "ADS-0003";
  f.kind = hil::UnitKind::kAds;
  f.strategy = "hysteresis_compensated";
  fm::AdsCalibrationConstants c = AdsConstants();
  c.altitude_ft.hysteresis.pressure_gain = -12.5;
  c.altitude_ft.hysteresis.pressure_gain_per_c = 0.25;
  c.altitude_ft.hysteresis.pressure_span = 3000.0;
  c.altitude_ft.hysteresis.thermal_gain = 4.0;
  c.altitude_ft.hysteresis.thermal_gain_per_c = -0.125;
  c.altitude_ft.hysteresis.thermal_span_c = 2.0;
  c.altitude_ft.hysteresis.die_temp_c = {25.0, 1e-5, 0.0, 0.0};
  f.ads = c;
  fm::AdsCalibrationConstants se = c;  // standard errors are >= 0
  se.altitude_ft.hysteresis.pressure_gain = 0.5;
  se.altitude_ft.hysteresis.pressure_gain_per_c = 0.0625;
  se.altitude_ft.hysteresis.thermal_gain_per_c = 0.03125;
  f.standard_errors = AdsStandardErrorsJson(se);
  json old = ToJson(f);
  for (json* h : {&old["constants"]["altitude_ft"]["hysteresis"],
                  &old["standard_errors"]["altitude_ft"]["hysteresis"]}) {
    for (const char* name : {"pressure_gain", "thermal_gain"}) {
      (*h)[std::string(name) + "_per_degc"] = (*h)[std::string(name) + "_per_c"];
      h->erase(std::string(name) + "_per_c");
    }
  }
  const ConstantsFile g = ConstantsFileFromJson(old, "old.json");
  ASSERT_TRUE(g.ads.has_value());
  EXPECT_EQ(g.ads->altitude_ft.hysteresis.pressure_gain_per_c, 0.25);
  EXPECT_EQ(g.ads->altitude_ft.hysteresis.thermal_gain_per_c, -0.125);
  EXPECT_EQ(g.standard_errors["altitude_ft"]["hysteresis"]["pressure_gain_per_c"], 0.0625);
  EXPECT_EQ(ToJson(g)["constants"], ToJson(f)["constants"]);
  old["constants"]["altitude_ft"]["hysteresis"]["pressure_gain_per_c"] = 0.25;
  EXPECT_THAT(MessageOf(old),
              HasSubstr("altitude_ft.hysteresis.pressure_gain_per_degc: the same as "
                        "pressure_gain_per_c, which is present too"));
}

// A file of the staged process names its stages; the reader takes them only from the first, in
// order, on an IMU's format-2 set, and the writer refuses to write anything else.
TEST(ConstantsFile, StagesRoundTripAndAreRefusedOutOfOrder) {
  ConstantsFile f = ImuFile();
  f.stages = {ImuStage::kThermal, ImuStage::kSensor};
  const json j = ToJson(f);
  EXPECT_EQ(j["stages"], json({"thermal", "sensor"}));
  EXPECT_EQ(ConstantsFileFromJson(j, "unit.json").stages, f.stages);
  EXPECT_FALSE(ToJson(ImuFile()).contains("stages"));  // a whole set says nothing

  json skipped = j;
  skipped["stages"] = {"thermal", "cross_axis"};
  EXPECT_THAT(MessageOf(skipped),
              HasSubstr("unit.json: $.stages[1]: expected \"sensor\" (the stages are held from "
                        "the first, in order), got \"cross_axis\""));
  json unknown = j;
  unknown["stages"] = {"thermal_drift"};
  EXPECT_THAT(MessageOf(unknown), HasSubstr("$.stages[0]: expected \"thermal\""));
  json empty = j;
  empty["stages"] = json::array();
  EXPECT_THAT(MessageOf(empty), HasSubstr("$.stages"));

  ConstantsFile a = ImuFile();
  a.serial = "ADS-0002";
  a.kind = hil::UnitKind::kAds;
  a.imu.reset();
  a.imu_diagnostics.reset();
  a.ads = AdsConstants();
  a.standard_errors = AdsStandardErrorsJson(*a.ads);
  json ads = ToJson(a);
  ads["stages"] = {"thermal"};
  EXPECT_THAT(MessageOf(ads), HasSubstr("$.stages: only an IMU is fitted in stages"));

  ConstantsFile out_of_order = ImuFile();
  out_of_order.stages = {ImuStage::kSensor};
  EXPECT_THROW(ToJson(out_of_order), ConstantsFileError);
}

TEST(ConstantsFile, UtcTimestampIsIso8601) {
  const std::string t = UtcNowIso8601();
  ASSERT_EQ(t.size(), 20u);
  EXPECT_EQ(t[4], '-');
  EXPECT_EQ(t[10], 'T');
  EXPECT_EQ(t.back(), 'Z');
}

}  // namespace
}  // namespace adahrs::calib
