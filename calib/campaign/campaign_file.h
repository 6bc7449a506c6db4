// The campaign file (docs/campaign.md): what `adahrs campaign` runs on a station, as a versioned
// JSON document outside the code. It names the sequence of each stage (the IMU calibration runs,
// fitted together; the ADS calibration run; the IMU and ADS acceptance runs), the strategy whose
// constants are downloaded per unit kind (IMU "joint", "reference" or an IMU strategy file; ADS
// "hysteresis_compensated" or "reference": the campaign fits both of each kind and downloads the
// one named), the specification file acceptance judges against (default: the AHR150A -A
// specification compiled in), the serial expected on each unit role of the stations (optional)
// and the retest policy (how many acceptance attempts a unit may have).
// Relative paths are taken from the campaign file's directory; Load returns them absolute.
// Every key is read strictly (common::ParamReader): an unknown key, a wrong type, a missing stage
// or an unknown strategy is refused naming the file and the JSON path.
// Left out: an operator entering or scanning serials at the start (the file carries them).
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "calib/campaign/campaign.h"

namespace adahrs::calib {

inline constexpr int kCampaignFileFormatVersion = 1;

struct CampaignFile {
  std::string name;
  CampaignSequences sequences;
  std::string imu_strategy = "joint";  ///< "joint", "reference" or a strategy file (absolute)
  std::string ads_strategy = "hysteresis_compensated";  ///< or "reference"
  /// Specification file; empty: the AHR150A -A specification compiled in.
  std::string specification_file;
  /// Expected serial (as IDENTIFY gives it, e.g. "IMU-000123") per station unit role ("imu1").
  std::map<std::string, std::string> expected_serials;
  int max_acceptance_attempts = 1;  ///< retest policy: attempts per unit, first included

  /// Reads `document`; relative paths are resolved against `base_dir`; errors name `source`.
  static CampaignFile FromJson(const nlohmann::json& document,
                               const std::string& source,
                               const std::filesystem::path& base_dir);
  /// Loads `path` (relative paths from its directory).
  static CampaignFile Load(const std::filesystem::path& path);
  nlohmann::json ToJson() const;
};

}  // namespace adahrs::calib
