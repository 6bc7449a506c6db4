#include "calib/imu_calibration/external_reply.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "calib/imu_calibration/external_protocol.h"
#include "calib/imu_calibration/imu_fit_result.h"
#include "common/imu_layout.h"
#include "common/printable_text.h"
#include "firmware_model/constants_exporter.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

void ImuScaleTemperatureNaN(firmware_model::ImuScaleTemperature* s, double nan) {
  s->active = true;
  for (auto& span : s->sensor) span = {nan, nan, nan};
  for (auto& channel : s->scale) channel = {nan, nan, nan, nan};
  s->accel_quadratic_per_g = {nan, nan, nan};
  for (auto& row : s->gs_dps_per_mps2) row = {nan, nan, nan};
}

[[noreturn]] void Refuse(const std::string& message) { throw std::runtime_error(message); }

json Parse(const std::string& bytes) {
  try {
    return json::parse(bytes);
  } catch (const json::exception& e) {  // a syntax error, or a number beyond a double
    Refuse("its standard output is not one JSON object (" + std::string(e.what()) +
           "); it began: " + "\"" + common::PrintableText(std::string_view(bytes).substr(0, 200)) +
           "\"");
  }
}

// Standard errors of the constants' shape, none estimated (a reply without any).
json NoStandardErrors(const json& constants) {
  firmware_model::ImuCalibrationConstants se = NotEstimated();
  if (constants.is_object() && constants.contains("scale_temperature")) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    ImuScaleTemperatureNaN(&se.scale_temperature, kNaN);
  }
  return ImuStandardErrorsJson(se);
}

// The reply's constants and standard errors, read by the constants file's own reader.
ConstantsFile ReadAsConstantsFile(const json& reply, const std::string& serial) {
  const json se = reply.contains("standard_errors") ? reply.at("standard_errors")
                                                    : NoStandardErrors(reply.at("constants"));
  const json file{
      {"format", kConstantsFormatName},
      {"format_version", kConstantsFormatVersion},
      {"serial", serial},
      {"kind", "imu"},
      {"strategy", "external"},
      {"created_utc", "2000-01-01T00:00:00Z"},
      {"software_version", "-"},
      {"constants", reply.at("constants")},
      {"standard_errors", se},
      {"provenance", {{"recordings", json::array()}, {"sequence_names", json::array()}}},
      {"diagnostics", json::object()}};
  try {
    return ConstantsFileFromJson(file, "the reply");
  } catch (const ConstantsFileError& e) {
    Refuse(e.what());
  }
}

void CheckFirmwareFormat(const firmware_model::ImuCalibrationConstants& c, int firmware_format) {
  if (c.scale_temperature.active != (firmware_format == 3)) {
    Refuse(firmware_format == 3
               ? "$.constants.scale_temperature: missing, and the strategy asks for format 3"
               : "$.constants.scale_temperature: present, and the strategy asks for format 2");
  }
  for (int ch = 0; ch < common::kImuChannelCount; ++ch) {
    if (c.thermal[ch].temp_sensor != common::kImuChannels[ch].thermometer) {
      Refuse("$.constants.thermal[" + std::to_string(ch) +
             "].temp_sensor: " + std::to_string(c.thermal[ch].temp_sensor) +
             ", the firmware compensates " + common::kImuChannels[ch].name + " with thermometer " +
             std::to_string(common::kImuChannels[ch].thermometer));
    }
  }
  try {
    firmware_model::ExportImuConstants(c);
  } catch (const std::invalid_argument& e) {
    Refuse("$.constants: not representable in the firmware's constant blocks: " +
           std::string(e.what()));
  }
}

std::vector<std::string> Log(const json& reply) {
  std::vector<std::string> log;
  if (!reply.contains("log")) return log;
  const json& lines = reply.at("log");
  if (!lines.is_array()) Refuse("$.log: expected an array of strings");
  for (size_t i = 0; i < lines.size(); ++i) {
    if (!lines[i].is_string()) Refuse("$.log[" + std::to_string(i) + "]: expected a string");
    log.push_back(lines[i].get<std::string>());
  }
  return log;
}

}  // namespace

CheckedReply CheckExternalReply(const std::string& reply_bytes,
                                const std::string& serial,
                                int firmware_format) {
  const json reply = Parse(reply_bytes);
  if (!reply.is_object())
    Refuse("its reply is JSON but not an object: " + reply.dump().substr(0, 80));
  for (const auto& [key, value] : reply.items()) {
    static const std::vector<std::string> kKeys = {"protocol",
                                                   "protocol_version",
                                                   "serial",
                                                   "constants",
                                                   "standard_errors",
                                                   "diagnostics",
                                                   "log"};
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
      Refuse("$." + key + ": unexpected key");
    }
  }
  for (const char* key : {"protocol", "protocol_version", "serial", "constants"}) {
    if (!reply.contains(key)) Refuse(std::string("$.") + key + ": missing");
  }
  if (reply.at("protocol") != kExternalReplyName) {
    Refuse("$.protocol: expected \"" + std::string(kExternalReplyName) + "\", got " +
           reply.at("protocol").dump());
  }
  if (reply.at("protocol_version") != kExternalProtocolVersion) {
    Refuse("$.protocol_version: expected " + std::to_string(kExternalProtocolVersion) + ", got " +
           reply.at("protocol_version").dump());
  }
  if (reply.at("serial") != serial) {
    Refuse("$.serial: the request was for " + serial + ", the reply is for " +
           reply.at("serial").dump());
  }
  if (reply.contains("diagnostics") && !reply.at("diagnostics").is_object()) {
    Refuse("$.diagnostics: expected an object");
  }
  const ConstantsFile file = ReadAsConstantsFile(reply, serial);
  CheckFirmwareFormat(*file.imu, firmware_format);
  return {*file.imu, file.standard_errors, Log(reply)};
}

}  // namespace adahrs::calib
