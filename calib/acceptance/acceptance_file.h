// acceptance.json (docs/acceptance.md, format "adahrs-acceptance" version 3): one file per unit
// with every judged point of an acceptance run (acceptance_judge.h), the unit's overall verdict and
// outcome (PASS, MARGINAL, FAIL) and its worst margin per quantity, the specification it was
// judged against (name, version, SHA-256 of its file) and the recording it came from (run id,
// SHA-256 of meta.json + imu.csv + ads.csv). Files are written atomically (temporary file + rename)
// as <out>/<serial>/acceptance.json. The file holds no time stamp: the same recording judged by the
// same software gives the same bytes, so the records (keyed by the file's SHA-256) hold it once
// however often it is judged. The reader is strict and typed (AcceptanceFile): a wrong format or
// version, a missing key or a wrong type is refused with the file and JSON path
// (AcceptanceFileError). Version 1 files, which lack noise and verdicts, read with noise =
// std_error and the verdict their pass implies; versions 1 and 2, which lack the marginal band and
// the specification's identity, read with band 0 (PASS or FAIL only) and an empty identity. Also
// here: the plain-text table `adahrs acceptance` prints.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/acceptance/acceptance_judge.h"

namespace adahrs::calib {

inline constexpr const char* kAcceptanceFormatName = "adahrs-acceptance";
/// 2 adds noise, physical limits, verdicts; 3 the specification's identity and the outcomes.
inline constexpr int kAcceptanceFormatVersion = 3;
inline constexpr const char* kAcceptanceFileName = "acceptance.json";

class AcceptanceFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The acceptance.json document of `unit` from `run`.
nlohmann::json AcceptanceJson(const AcceptanceRun& run,
                              const UnitAcceptance& unit,
                              const Specification& spec,
                              const std::string& software_version);

/// Writes <out_dir>/<serial>/acceptance.json for every unit of `run`; returns the paths.
std::vector<std::filesystem::path> WriteAcceptanceFiles(const AcceptanceRun& run,
                                                        const Specification& spec,
                                                        const std::string& software_version,
                                                        const std::filesystem::path& out_dir);

/// The recording an acceptance.json judged.
struct AcceptanceFileRun {
  std::string dir;
  std::string run_id;
  std::string sequence;
  std::string recording_sha256;
};

/// Which specification the file was judged against (empty for files before version 3).
struct AcceptanceFileSpecification {
  std::string name;
  std::string version;
  std::string sha256;  ///< of the specification file's bytes
};

/// What the physical limits of the rate points were computed from.
struct AcceptanceFileLimit {
  double since_calibration_h = 0.0;
  double rest_record_s = 0.0;
  double rest_chamber_c = 0.0;
};

/// One acceptance.json, read back: the unit's judged points (their verdicts, worst margins and
/// counts follow from them as when judged) and what the file says about where they came from.
struct AcceptanceFile {
  std::filesystem::path source;
  int format_version = 0;
  std::string software_version;
  AcceptanceFileRun run;
  UnitAcceptance unit;  ///< serial, kind, mode and points; no rest record (see physical_limit)
  std::optional<AcceptanceFileLimit> physical_limit;
  AcceptanceFileSpecification specification_id;
  nlohmann::json specification;  ///< Specification::ToJson as written (shown, not judged again)
};

/// Reads and validates an acceptance.json; throws AcceptanceFileError naming file and JSON path.
AcceptanceFile ReadAcceptanceFile(const std::filesystem::path& file);

/// Every acceptance.json under `dir` (the layout WriteAcceptanceFiles makes), sorted by path.
std::vector<std::filesystem::path> FindAcceptanceFiles(const std::filesystem::path& dir);

/// "body-rate points: 12 of 63 within specification, 51 outside specification, within the physical
/// limit, 0 outside specification and the physical limit (physical limit 0.1...0.2 deg/s)\n", or
/// "" for a unit without rate points: the line the acceptance table and the demo summary share.
std::string RateVerdictLine(const UnitAcceptance& unit);

/// One line per judged point and a verdict line per unit, for the terminal.
std::string AcceptanceText(const AcceptanceRun& run);

}  // namespace adahrs::calib
