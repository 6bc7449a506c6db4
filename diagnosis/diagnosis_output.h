// `adahrs diagnose` end to end on run directories: every IMU and ADS unit of the recordings (or
// one) diagnosed against the pipeline's forward model (imu_diagnosis.h, ads_diagnosis.h), written
// as OUT/diagnosis.json (format "adahrs-diagnosis", docs/diagnose.md) and OUT/report.html (findings
// in words, located structure, residual figures before and after, detection limits). Runs whose
// meta.json lists ADS units are read for their calibration points (SelectAdsCalibrationPoints) and
// each ADS unit is diagnosed per run (ads_diagnosis.h); the others by LoadImuRuns (calibration rows
// of raw-mode steps). Refusals name the file, line and column. Generic channel CSVs (a sidecar JSON
// each) go through DiagnoseChannelFiles.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "diagnosis/imu_diagnosis.h"

namespace adahrs::diagnosis {

inline constexpr int kDiagnosisFormatVersion = 1;

struct DiagnosisRun {
  std::vector<calib::RecordingReference> recordings;
  std::string model;  ///< what the recordings were compared with
  std::vector<UnitDiagnosis> units;
  std::vector<std::string> notes;  ///< about the recordings as read (columns ignored, ...)
  nlohmann::json ToJson() const;
};

/// Reads the runs and diagnoses every unit (or only `serial`); throws ImuInputError,
/// hil::RecordingError or std::runtime_error with the reason, and ImuInputError when `serial` is
/// not in the runs.
DiagnosisRun DiagnoseRuns(const std::vector<std::filesystem::path>& runs,
                          const std::optional<std::string>& serial,
                          const DiagnosisOptions& options = {});

/// Diagnoses each generic channel recording (a JSON sidecar and the CSV it names,
/// channel_recording.h) against the generic model (channel_diagnosis.h); throws
/// ChannelInputError naming the file, JSON path or line and column.
DiagnosisRun DiagnoseChannelFiles(const std::vector<std::filesystem::path>& sidecars,
                                  const DiagnosisOptions& options = {});

/// report.html of a diagnosis.
std::string DiagnosisHtml(const DiagnosisRun& run);

/// Writes OUT/diagnosis.json and OUT/report.html (creating OUT); throws std::runtime_error naming
/// the file it could not write.
void WriteDiagnosis(const DiagnosisRun& run, const std::filesystem::path& out_dir);

}  // namespace adahrs::diagnosis
