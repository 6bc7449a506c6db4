// constants.json (docs/constants-file.md): one file per calibrated unit holding the
// double-precision firmware constants (firmware_model/calibration_constants.h) with the 1-sigma
// standard error of every number (null where none), the strategy that produced them, the
// provenance (the recordings' SHA-256 and sequence names) needed to reproduce or audit them, and
// the fit's diagnostics typed by the unit's kind. Units are those of the constants themselves.
// The reader is strict: a missing or unexpected key, a wrong type, format or version, a negative
// standard error or one whose shape differs from the constants' is refused with ConstantsFileError
// naming the file and the JSON path.
// Not held: the fixed-point blocks (constants_exporter.h derives them), covariances between
// constants (only the standard errors), the recordings themselves.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/constants/ads_fit_diagnostics.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "calib/constants/imu_stage.h"
#include "firmware_model/calibration_constants.h"
#include "hil/station.h"
#include "hil/utc_time.h"

namespace adahrs::calib {

class ConstantsFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Version 3 adds the IMU's "scale_temperature" (firmware constants format 3); a file is written
/// as version 2 when it has none, so files of format-2 constants read in older software.
inline constexpr int kConstantsFormatVersion = 3;
inline constexpr int kConstantsOldestFormatVersion = 2;
inline constexpr const char* kConstantsFormatName = "adahrs-constants";

struct RecordingReference {
  std::string path;    ///< run directory as given to the fit
  std::string sha256;  ///< RecordingSha256 (recording_checksum.h), 64 lowercase hex digits
  bool operator==(const RecordingReference&) const = default;
};

/// An external strategy's fit (docs/strategies-external.md "What is kept"): the program run and
/// the SHA-256 of the strategy file and of the request and reply bytes kept beside the file.
struct ExternalFitRecord {
  std::vector<std::string> program;
  std::string strategy_file;  ///< absolute path of the strategy file the program came from
  std::string strategy_sha256;
  std::string request_sha256;
  std::string reply_sha256;
  bool operator==(const ExternalFitRecord&) const = default;
};

struct ConstantsProvenance {
  std::vector<RecordingReference> recordings;
  std::vector<std::string> sequence_names;
  std::optional<ExternalFitRecord> external;  ///< "external" in the JSON, an external fit's only
  bool operator==(const ConstantsProvenance&) const = default;
};

struct ConstantsFile {
  std::string serial;  ///< "IMU-0001" / "ADS-0001" (UnitSerialText)
  hil::UnitKind kind = hil::UnitKind::kImu;
  std::string strategy;
  std::string created_utc;  ///< ISO 8601, e.g. 2024-05-01T12:00:00Z
  std::string software_version;
  std::optional<firmware_model::ImuCalibrationConstants> imu;  ///< set when kind is kImu
  std::optional<firmware_model::AdsCalibrationConstants> ads;  ///< set when kind is kAds
  nlohmann::json standard_errors;  ///< same shape as ToJson(constants); null = not estimated
  ConstantsProvenance provenance;
  std::optional<ImuFitDiagnostics> imu_diagnostics;  ///< kind kImu; absent: written as {}
  std::optional<AdsFitDiagnostics> ads_diagnostics;  ///< kind kAds; absent: written as {}
  /// IMU, staged process (imu_stage.h): the stages whose constants this file holds, from the
  /// first in order ("stages" in the JSON); the later ones hold their defaults (offset 0, scale
  /// 0.04 duty/g, gyro polynomial 0, cross-axis the identity). Empty: the whole set.
  std::vector<ImuStage> stages;
};

/// The standard-error JSON of an IMU set from a struct holding the standard errors in place of
/// the values: NaN becomes null (not estimated); temp_sensor (a choice, not an estimate) is null.
nlohmann::json ImuStandardErrorsJson(const firmware_model::ImuCalibrationConstants& se);
/// Likewise for ADS; the code box (a property of the data, not an estimate), the law, the
/// hysteresis spans (nominal parameters) and the die temperature's origin are null.
nlohmann::json AdsStandardErrorsJson(const firmware_model::AdsCalibrationConstants& se);

/// The standard errors of an IMU file as a constants struct (null -> NaN; temp_sensor copied
/// from the constants). Throws ConstantsFileError when the file is not an IMU's.
firmware_model::ImuCalibrationConstants ImuStandardErrors(const ConstantsFile& file);

/// The file's JSON; throws ConstantsFileError if the file is inconsistent (kind without its
/// constants, standard errors of another shape, a negative standard error).
nlohmann::json ToJson(const ConstantsFile& file);
/// Parses and validates; `source` (a path) leads every message.
ConstantsFile ConstantsFileFromJson(const nlohmann::json& json, const std::string& source);

/// Reads and validates a file.
ConstantsFile ReadConstantsFile(const std::filesystem::path& path);
/// Writes atomically (temporary file + rename); throws ConstantsFileError naming the path.
void WriteConstantsFile(const std::filesystem::path& path, const ConstantsFile& file);

/// The current UTC time as ISO 8601 with seconds ("2024-05-01T12:00:00Z").
using hil::UtcNowIso8601;

}  // namespace adahrs::calib
