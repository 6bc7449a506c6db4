#include "calib/constants/constants_file.h"

#include <cmath>
#include <ctime>
#include <limits>

#include "common/atomic_file.h"
#include "common/param_reader.h"
#include "common/unit_kind.h"

namespace adahrs::calib {
namespace {

using common::ParamError;
using common::ParamReader;
using nlohmann::json;

// NaN numbers become null, recursively.
json NullForNaN(json j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return nullptr;
  if (j.is_structured()) {
    for (auto& item : j) item = NullForNaN(item);
  }
  return j;
}

// Checks that `se` has the shape of `value` (objects with the same keys, arrays of the same
// length) and that every number of `value` faces a non-negative finite number or null.
void CheckShape(const json& value,
                const json& se,
                const std::string& where,
                const std::string& source) {
  auto fail = [&](const std::string& message) {
    throw ConstantsFileError(source + ": " + where + ": " + message);
  };
  if (value.is_object()) {
    if (!se.is_object()) fail("expected an object like the constants");
    for (const auto& [key, item] : value.items()) {
      if (!se.contains(key)) fail("missing key \"" + key + "\" (the constants have it)");
      CheckShape(item, se.at(key), where + "." + key, source);
    }
    for (const auto& [key, item] : se.items()) {
      if (!value.contains(key)) fail("unexpected key \"" + key + "\" (not in the constants)");
    }
  } else if (value.is_array()) {
    if (!se.is_array() || se.size() != value.size()) {
      fail("expected an array of " + std::to_string(value.size()) + " like the constants");
    }
    for (size_t i = 0; i < value.size(); ++i) {
      CheckShape(value[i], se[i], where + "[" + std::to_string(i) + "]", source);
    }
  } else if (value.is_number()) {
    if (se.is_null()) return;
    if (!se.is_number()) fail("expected a standard error (number) or null");
    const double x = se.get<double>();
    if (!std::isfinite(x) || x < 0.0)
      fail("a standard error must be finite and >= 0, got " + se.dump());
  } else if (value.is_string()) {
    // A named choice (an ADS surface's law), not an estimate: its standard error is null.
    if (!se.is_null()) fail("expected null (a named choice has no standard error)");
  } else {
    fail("unexpected value type in the constants");
  }
}

bool IsSha256Hex(const std::string& s) {
  if (s.size() != 64) return false;
  for (char c : s) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

json ConstantsJson(const ConstantsFile& file, const std::string& source) {
  if (file.kind == hil::UnitKind::kImu) {
    if (!file.imu || file.ads)
      throw ConstantsFileError(source + ": kind imu needs IMU constants only");
    return firmware_model::ToJson(*file.imu);
  }
  if (!file.ads || file.imu)
    throw ConstantsFileError(source + ": kind ads needs ADS constants only");
  return firmware_model::ToJson(*file.ads);
}

ExternalFitRecord ParseExternalRecord(const ParamReader& provenance, const json& external) {
  const ParamReader r = provenance.Child("external");
  ExternalFitRecord e;
  const size_t n = r.ArrayLength("program", 1, 256);
  for (size_t i = 0; i < n; ++i) {
    const json& arg = external.at("program").at(i);
    if (!arg.is_string())
      r.Fail(r.path() + ".program[" + std::to_string(i) + "]", "expected a string");
    e.program.push_back(arg.get<std::string>());
  }
  e.strategy_file = r.String("strategy_file");
  for (auto [key, sha] : {std::pair{"strategy_sha256", &e.strategy_sha256},
                          std::pair{"request_sha256", &e.request_sha256},
                          std::pair{"reply_sha256", &e.reply_sha256}}) {
    *sha = r.String(key);
    if (!IsSha256Hex(*sha)) {
      r.Fail(r.path() + "." + key, "expected 64 lowercase hex digits, got \"" + *sha + "\"");
    }
  }
  r.ExpectAllKeysUsed();
  return e;
}

ConstantsFile Parse(const json& j, const std::string& source) {
  const ParamReader reader(j, source);
  ConstantsFile file;
  const std::string format = reader.String("format");
  if (format != kConstantsFormatName) {
    reader.Fail("$.format",
                "expected \"" + std::string(kConstantsFormatName) + "\", got \"" + format + "\"");
  }
  const int64_t version = reader.Integer("format_version", 0, 1 << 20);
  if (version < kConstantsOldestFormatVersion || version > kConstantsFormatVersion) {
    reader.Fail("$.format_version",
                "version " + std::to_string(version) +
                    " is not supported (this software reads versions " +
                    std::to_string(kConstantsOldestFormatVersion) + " to " +
                    std::to_string(kConstantsFormatVersion) + ")");
  }
  file.serial = reader.String("serial");
  if (file.serial.empty()) reader.Fail("$.serial", "empty");
  const std::string kind = reader.String("kind");
  const std::optional<hil::UnitKind> parsed = common::ParseUnitKind(kind);
  if (!parsed) reader.Fail("$.kind", "expected \"imu\" or \"ads\", got \"" + kind + "\"");
  file.kind = *parsed;
  file.strategy = reader.String("strategy");
  file.created_utc = reader.String("created_utc");
  file.software_version = reader.String("software_version");

  reader.Child("constants");
  const json& constants = j.at("constants");
  if (version < 3 && constants.is_object() && constants.contains("scale_temperature")) {
    reader.Fail("$.constants.scale_temperature",
                "needs format_version 3, the file says " + std::to_string(version));
  }
  try {
    if (file.kind == hil::UnitKind::kImu) {
      file.imu = firmware_model::ImuCalibrationConstantsFromJson(constants, "$.constants");
    } else {
      file.ads = firmware_model::AdsCalibrationConstantsFromJson(constants, "$.constants");
    }
  } catch (const std::runtime_error& e) {
    throw ConstantsFileError(source + ": " + e.what());
  }
  reader.Child("standard_errors");
  file.standard_errors = j.at("standard_errors");
  CheckShape(constants, file.standard_errors, "$.standard_errors", source);
  if (file.ads) {  // the constants were read under today's key names; so are their errors
    file.standard_errors =
        firmware_model::WithCurrentAdsKeys(file.standard_errors, "$.standard_errors");
  }

  const ParamReader provenance = reader.Child("provenance");
  const size_t n = provenance.ArrayLength("recordings", 0, 1000);
  for (size_t i = 0; i < n; ++i) {
    const ParamReader r = provenance.Element("recordings", i, n);
    RecordingReference ref{r.String("path"), r.String("sha256")};
    if (!IsSha256Hex(ref.sha256)) {
      r.Fail(r.path() + ".sha256", "expected 64 lowercase hex digits, got \"" + ref.sha256 + "\"");
    }
    r.ExpectAllKeysUsed();
    file.provenance.recordings.push_back(ref);
  }
  provenance.ArrayLength("sequence_names", 0, 1000);
  for (const json& name : j.at("provenance").at("sequence_names")) {
    if (!name.is_string()) provenance.Fail("$.provenance.sequence_names", "expected strings");
    file.provenance.sequence_names.push_back(name.get<std::string>());
  }
  if (provenance.Has("external"))
    file.provenance.external = ParseExternalRecord(provenance, j.at("provenance").at("external"));
  provenance.ExpectAllKeysUsed();
  if (reader.Has("stages")) {
    if (file.kind != hil::UnitKind::kImu)
      reader.Fail("$.stages", "only an IMU is fitted in stages");
    if (file.imu->scale_temperature.active) {
      reader.Fail("$.stages", "a staged fit holds format-2 constants, this file format-3 terms");
    }
    const size_t count = reader.ArrayLength("stages", 1, std::size(kImuStages));
    for (size_t i = 0; i < count; ++i) {
      const json& name = j.at("stages").at(i);
      const std::optional<ImuStage> stage =
          name.is_string() ? ParseImuStage(name.get<std::string>()) : std::nullopt;
      if (!stage || *stage != kImuStages[i]) {
        reader.Fail("$.stages[" + std::to_string(i) + "]",
                    "expected \"" + std::string(ImuStageName(kImuStages[i])) +
                        "\" (the stages are held from the first, in order), got " + name.dump());
      }
      file.stages.push_back(*stage);
    }
  }
  reader.Child("diagnostics");
  const json& diagnostics = j.at("diagnostics");
  if (file.kind == hil::UnitKind::kImu) {
    file.imu_diagnostics = ImuFitDiagnostics::FromJson(diagnostics, source);
  } else if (!(diagnostics.is_object() && diagnostics.empty())) {
    file.ads_diagnostics = AdsFitDiagnostics::FromJson(diagnostics, source);
  }
  reader.ExpectAllKeysUsed();
  return file;
}

// The diagnostics of the file's kind; a section of the other kind is an inconsistent file.
json DiagnosticsJson(const ConstantsFile& file, const std::string& source) {
  const bool imu = file.kind == hil::UnitKind::kImu;
  if (imu ? file.ads_diagnostics.has_value() : file.imu_diagnostics.has_value()) {
    throw ConstantsFileError(source + ": $.diagnostics: diagnostics of the other unit kind");
  }
  if (file.imu_diagnostics) return file.imu_diagnostics->ToJson();
  if (file.ads_diagnostics) return file.ads_diagnostics->ToJson();
  return json::object();
}

}  // namespace

json ImuStandardErrorsJson(const firmware_model::ImuCalibrationConstants& se) {
  json j = NullForNaN(firmware_model::ToJson(se));
  for (json& t : j["thermal"]) {
    t["temp_sensor"] = nullptr;
    t["temp_min_cnt"] = nullptr;
    t["temp_max_cnt"] = nullptr;
  }
  if (j.contains("scale_temperature")) {  // the spans are chosen, not estimated
    for (json& s : j["scale_temperature"]["sensor"]) {
      for (const char* key : {"origin_cnt", "min_cnt", "max_cnt"}) s[key] = nullptr;
    }
  }
  return j;
}

json AdsStandardErrorsJson(const firmware_model::AdsCalibrationConstants& se) {
  json j = NullForNaN(firmware_model::ToJson(se));
  for (const char* surface : {"altitude_ft", "airspeed_kt"}) {
    for (const char* key : {"x_min_code", "x_max_code", "y_min_code", "y_max_code", "law"}) {
      j[surface][key] = nullptr;
    }
    if (j[surface].contains("hysteresis")) {  // spans: nominal parameters, not estimates
      for (const char* key : {"pressure_span", "thermal_span_c", "die_temp_origin_code"}) {
        j[surface]["hysteresis"][key] = nullptr;
      }
    }
    if (j[surface].contains("y_linearisation")) {  // the origin is a chosen whole code
      j[surface]["y_linearisation"]["origin_code"] = nullptr;
    }
  }
  return j;
}

firmware_model::ImuCalibrationConstants ImuStandardErrors(const ConstantsFile& file) {
  if (!file.imu) throw ConstantsFileError(file.serial + ": not an IMU constants file");
  const json& j = file.standard_errors;
  auto number = [](const json& x) {
    return x.is_number() ? x.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  firmware_model::ImuCalibrationConstants se = *file.imu;
  for (size_t ch = 0; ch < 9; ++ch) {
    for (size_t i = 0; i < 4; ++i) se.thermal[ch].k[i] = number(j["thermal"][ch]["k"][i]);
  }
  for (size_t ch = 0; ch < 6; ++ch) {
    se.accel[ch] = {number(j["accel"][ch]["offset_duty"]),
                    number(j["accel"][ch]["scale_duty_per_g"])};
  }
  for (size_t g = 0; g < 3; ++g) {
    se.gyro[g].null_cnt = number(j["gyro"][g]["null_cnt"]);
    for (size_t i = 0; i < 4; ++i) se.gyro[g].l[i] = number(j["gyro"][g]["l"][i]);
  }
  for (size_t r = 0; r < 3; ++r) {
    for (size_t k = 0; k < 3; ++k) {
      se.ca_mps2_per_g[r][k] = number(j["ca_mps2_per_g"][r][k]);
      se.cg[r][k] = number(j["cg"][r][k]);
    }
  }
  if (se.scale_temperature.active) {
    const json& st = j["scale_temperature"];
    for (size_t c = 0; c < 9; ++c) {
      for (size_t i = 0; i < 4; ++i) se.scale_temperature.scale[c][i] = number(st["scale"][c][i]);
    }
    for (size_t a = 0; a < 3; ++a) {
      se.scale_temperature.accel_quadratic_per_g[a] = number(st["accel_quadratic_per_g"][a]);
      for (size_t k = 0; k < 3; ++k) {
        se.scale_temperature.gs_dps_per_mps2[a][k] = number(st["gs_dps_per_mps2"][a][k]);
      }
    }
  }
  return se;
}

json ToJson(const ConstantsFile& file) {
  const std::string source = "constants of " + file.serial;
  const json constants = ConstantsJson(file, source);
  CheckShape(constants, file.standard_errors, "$.standard_errors", source);
  json recordings = json::array();
  for (const RecordingReference& r : file.provenance.recordings) {
    if (!IsSha256Hex(r.sha256)) {
      throw ConstantsFileError(source + ": recording " + r.path + ": not a SHA-256: " + r.sha256);
    }
    recordings.push_back({{"path", r.path}, {"sha256", r.sha256}});
  }
  json provenance{{"recordings", recordings}, {"sequence_names", file.provenance.sequence_names}};
  if (const auto& e = file.provenance.external) {
    for (const std::string* sha : {&e->strategy_sha256, &e->request_sha256, &e->reply_sha256}) {
      if (!IsSha256Hex(*sha)) {
        throw ConstantsFileError(source + ": $.provenance.external: not a SHA-256: " + *sha);
      }
    }
    provenance["external"] = {{"program", e->program},
                              {"strategy_file", e->strategy_file},
                              {"strategy_sha256", e->strategy_sha256},
                              {"request_sha256", e->request_sha256},
                              {"reply_sha256", e->reply_sha256}};
  }
  const bool format3 = file.imu && file.imu->scale_temperature.active;
  json j{{"format", kConstantsFormatName},
         {"format_version", format3 ? kConstantsFormatVersion : kConstantsOldestFormatVersion},
         {"serial", file.serial},
         {"kind", common::UnitKindName(file.kind)},
         {"strategy", file.strategy},
         {"created_utc", file.created_utc},
         {"software_version", file.software_version},
         {"constants", constants},
         {"standard_errors", file.standard_errors},
         {"provenance", provenance},
         {"diagnostics", NullForNaN(DiagnosticsJson(file, source))}};
  if (!file.stages.empty()) {
    if (file.kind != hil::UnitKind::kImu || format3 ||
        file.stages != StagesThrough(file.stages.back())) {
      throw ConstantsFileError(source +
                               ": $.stages: an IMU's format-2 stages from the first, in order");
    }
    json stages = json::array();
    for (ImuStage stage : file.stages) stages.push_back(std::string(ImuStageName(stage)));
    j["stages"] = stages;
  }
  return j;
}

ConstantsFile ConstantsFileFromJson(const json& j, const std::string& source) {
  try {
    return Parse(j, source);
  } catch (const ParamError& e) {
    throw ConstantsFileError(e.what());
  }
}

ConstantsFile ReadConstantsFile(const std::filesystem::path& path) {
  json j;
  try {
    j = ParamReader::LoadFile(path.string());
  } catch (const ParamError& e) {
    throw ConstantsFileError(e.what());
  }
  return ConstantsFileFromJson(j, path.string());
}

void WriteConstantsFile(const std::filesystem::path& path, const ConstantsFile& file) {
  try {
    common::WriteFileAtomically(path, ToJson(file).dump(2) + "\n");
  } catch (const common::AtomicWriteError& e) {
    throw ConstantsFileError(e.what());
  }
}

}  // namespace adahrs::calib
