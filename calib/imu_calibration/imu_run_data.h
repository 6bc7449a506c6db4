// The calibration data of each IMU in one or more recordings, selected as the executor defines it
// (the step's TAG and index, outside meta.json's rejected intervals) and grouped per unit serial
// and acquisition: one per accel step, one per reported table rate of a gyro step, one per
// (orientation, reported rate) of a cross_axis step, and every thermal_profile row labelled
// up-ramp, down-ramp or soak from the chamber's reported trend (each run's clock starts at zero).
// Rows that cannot be calibration data (undefined duty, saturated counts, not raw mode) are
// excluded and reported with file, line and column; bad input is refused with ImuInputError
// naming the run, step and unit (hil::RecordingError passes through).
// Units: duty (accelerometers), counts (gyros, TEMP), deg/s (table rates), m/s^2 (local gravity).
// Selection rules, trend labelling, exclusions and refusals: docs/calibration-strategies.md
// ("Selecting the calibration data").
// Left out: any fitting; interpretation of the temperature counts (the strategies decide).
#pragma once

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "calib/constants/constants_file.h"
#include "calib/sequence/sequence.h"
#include "calib/solvers/thermal_drift_fit.h"
#include "firmware_model/unit_firmware.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {

class ImuInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One received packet of calibration data.
struct ImuSample {
  firmware_model::ImuRawFrame raw{};
  double t_s = 0.0;
  double chamber_c = 0.0;
  double table_rate_dps = 0.0;
  int run = 0;      ///< index of its run in LoadImuRuns' order (ImuRunData::recordings)
  uint8_t seq = 0;  ///< the packet's 8-bit sequence counter
};

/// The rows of one acquisition (one orientation and one table rate).
struct ImuAcquisition {
  std::string run;        ///< run directory
  int step = 0;           ///< step index in the run's sequence
  std::string step_kind;  ///< "accel", "gyro", "cross_axis"
  int orientation = 0;    ///< 11...32
  double rate_dps = 0.0;  ///< mean reported table rate about the up axis (0 at rest)
  std::vector<ImuSample> samples;
};

struct ImuUnitData {
  std::string serial;
  std::vector<ImuSample> thermal;               ///< thermal_profile rows, time order
  std::vector<ThermalSegment> thermal_segment;  ///< one per thermal row
  int thermal_orientation = 0;                  ///< the orientation the profile ran in (0 unknown)
  std::vector<ImuAcquisition> accel;
  std::vector<ImuAcquisition> gyro;
  std::vector<ImuAcquisition> cross_axis;
  std::vector<std::string> exclusions;  ///< one message per excluded row (file, line, column)
  int rejected_interval_rows = 0;       ///< rows dropped because a rejected interval holds them
};

struct ImuRunData {
  double local_gravity_mps2 = 0.0;
  std::vector<RecordingReference> recordings;  ///< with their SHA-256
  std::vector<std::string> sequence_names;
  std::map<std::string, ImuUnitData> units;  ///< by serial
  std::vector<std::string> notes;            ///< what the recording reader passed over
};

/// A row's raw counts as the firmware takes them (every mode's packet carries them).
firmware_model::ImuRawFrame RawFrameOf(const hil::ImuRecordRow& row);

/// Reads every run directory and collects each IMU's calibration data; throws ImuInputError or
/// hil::RecordingError with the reason.
ImuRunData LoadImuRuns(const std::vector<std::filesystem::path>& run_dirs);

/// Collects one run's rows into `data` by the rules above, from rows handed over one at a time:
/// a recording streamed from disk (LoadImuRuns) or a run simulated in memory (calib/studies).
/// The constructor and Finish throw ImuInputError naming `run`.
class ImuRunCollector {
 public:
  ImuRunCollector(std::string run,
                  std::string sha256,
                  const Sequence& sequence,
                  double local_gravity_mps2,
                  std::vector<std::string> serials,
                  std::vector<hil::RejectedInterval> rejected,
                  ImuRunData* data);
  /// Selects or excludes one row (`line`: its line in imu.csv, for exclusion messages).
  void Take(const hil::ImuRecordRow& row, int line);
  /// Groups the selected rows into acquisitions and labels the thermal rows.
  void Finish();

 private:
  // The rows selected for one (unit, step): each sample with its row's fixture orientation.
  struct SelectedRows {
    std::vector<int> orientation;
    std::vector<ImuSample> samples;
  };

  [[noreturn]] void Fail(const std::string& message) const;
  void ReserveThermalRows();

  std::string run_;
  Sequence sequence_;
  std::vector<uint8_t> tags_;
  std::vector<std::string> serials_;
  std::vector<hil::RejectedInterval> rejected_;
  ImuRunData* data_;
  int run_index_ = 0;
  std::map<std::pair<std::string, int>, SelectedRows> selected_;
  // The previous row's unit and step with their entries: the consecutive rows of one unit and
  // step (a one-unit run's) skip the look-ups.
  std::string cached_unit_;
  int cached_step_ = -1;
  ImuUnitData* cached_data_ = nullptr;
  SelectedRows* cached_rows_ = nullptr;
};

/// Labels every unit's thermal rows up-ramp, down-ramp or soak (the rule above).
void LabelThermalSegments(ImuRunData* data);

/// Unit vector of the up axis of `orientation` in B (11 -> +x_B, 12 -> -x_B, ..., 32 -> -z_B).
std::array<double, 3> UpAxisOf(int orientation);

}  // namespace adahrs::calib
