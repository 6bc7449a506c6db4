// A run's meta.json (docs/recording-format.md "meta.json") as one typed record: what the run was
// (station, sequence, units, instruments), its time base and status, and the intervals whose rows
// are not calibration data. Every reader and writer of meta.json goes through FromJson/ToJson, so
// "missing" means one thing everywhere and every refusal names the file and the JSON path.
// The station and the sequence are kept as the JSON that was written: the station file's schema is
// hil::Station's, the sequence language is calib's (SequenceFromJson); each reads its own.
// Keys only some producers write (a simulation's model_profile, orientation, log_every and chamber
// ramps; a replay's "replay") are kept in `extra`, as written. The units' line timing and the
// resume times bound the recording's sample times (hil/recording/sample_time_check.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/unit_kind.h"

namespace adahrs::hil {

/// A span of the run whose rows are not calibration data (a failed interlock, the first attempt of
/// a step repeated after a resume).
struct RejectedInterval {
  int step = 0;            ///< index of the sequence step the interval belongs to
  double t_start_s = 0.0;  ///< first rejected time on the run's time base, inclusive
  double t_end_s = 0.0;    ///< last rejected time, inclusive
  std::string reason;
};

/// One unit of the batch as the run found it ($.units[i]).
struct RecordingUnit {
  std::string role;
  std::optional<common::UnitKind> kind;  ///< "imu" or "ads" in the file; absent if not said
  std::string serial;                    ///< "IMU-0001"; empty when the producer did not say
  std::optional<int64_t> serial_number;
  std::optional<std::string> firmware;  ///< "M.m.p", or "simulated"
  std::optional<int64_t> slot;
  std::optional<int64_t> constants_version;
  std::optional<int64_t> mode;
  /// The unit's line as its frames were counted on (docs/recording-format.md "Sample time"): the
  /// longest a packet waits between its sample and its arrival, s, and how fast the unit's clock
  /// may run apart from the run's, ppm. Absent: the recording states no bound (not checked).
  std::optional<double> line_buffering_s;
  std::optional<double> clock_drift_ppm;
};

/// What an instrument of the batch said it is ($.instruments[i]).
struct RecordingInstrument {
  std::string role;
  std::string model;
  std::string detail;
};

struct RecordingMeta {
  int format_version = 0;
  std::optional<std::string> run_id;
  std::optional<std::string> started_utc;
  std::optional<std::string> status;       ///< "running", "complete", "aborted", "interrupted"
  std::optional<nlohmann::json> station;   ///< the station file as the executor read it
  std::optional<nlohmann::json> sequence;  ///< the sequence JSON
  std::optional<std::string> sequence_file;
  std::optional<std::string> time_base;
  std::optional<double> sample_rate_hz;
  std::optional<double> local_gravity_mps2;
  std::vector<RecordingUnit> units;
  bool has_units = false;  ///< $.units present (a recording may not list its units)
  std::optional<std::vector<RecordingInstrument>> instruments;
  std::vector<RejectedInterval> rejected_intervals;
  bool has_rejected_intervals = false;
  /// The run's time at which each resume began, ascending ($.resumed_t_s; empty when none).
  std::vector<double> resumed_t_s;
  nlohmann::json extra = nlohmann::json::object();  ///< other keys, as written

  /// The unit of `serial`, or nullptr.
  const RecordingUnit* Unit(const std::string& serial) const;

  nlohmann::json ToJson() const;
  /// Reads meta.json's object; throws RecordingError naming `source` and the JSON path.
  static RecordingMeta FromJson(const nlohmann::json& meta, const std::string& source);
};

/// meta.json's "rejected_intervals" array of `intervals`.
nlohmann::json RejectedIntervalsJson(const std::vector<RejectedInterval>& intervals);

}  // namespace adahrs::hil
