// Refusing invalid sequences before anything moves. Every problem is collected, none stops the
// check: each names the file, the JSON path of the offending value, the rule broken and, when a
// limit is exceeded, the instrument or unit limit with its value (SequenceLimits).
//
// Rules (docs/sequences.md "Validation" lists them for users):
//   structure   at least one step; step kinds allowed for the sequence's unit kind (accel, gyro,
//               cross_axis on IMU sequences; altitude, airspeed, log on ADS sequences);
//   TAG         1…255, unique among explicit TAGs, enough free TAGs for the steps without one;
//   orientation one of 11, 12, 21, 22, 31, 32;
//   acquisition packets 1…max_packets, log duration in (0, max_log_duration_s];
//   gyro        rate_min ≤ rate_max, increment > 0 and a whole number of increments from min to
//               max; every rate within the gyro range and the table's rate limit; the table
//               acceleration within the table's limit;
//   cross_axis  rate within the gyro range and the table's rate limit, accel within the table's;
//   temperature every target (and F4 idle set point) inside the unit's rating and the chamber's
//               range; band > 0; soak ≥ 0;
//   profile     name of 1…10 A–Z, 0–9 or space; 1…chamber_max_profile_steps steps; one end step,
//               the last; ramp rate in (0, chamber_max_ramp]; ramp-time ramps no faster than that;
//               durations in (0, chamber_max_step_duration]; jumps only backwards to a ramp or
//               soak step, count 1…chamber_max_jump_count;
//   altitude    inside the unit's and the ADTS's range, static pressure below the ADS static
//               limit; rate in (0, min(ADS safe rate, ADTS max rate)];
//   airspeed    0…min(unit, ADTS) limit, impact pressure below the pitot limit; rate likewise;
//   prompt      non-empty text.
// Not checked: anything the sequence does not state (interlock thresholds, station wiring).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "calib/sequence/sequence.h"
#include "calib/sequence/sequence_limits.h"

namespace adahrs::calib {

/// One reason a sequence is refused.
struct SequenceProblem {
  std::string path;   ///< JSON path, e.g. "$.steps[3].rate_max_dps"
  std::string rule;   ///< the rule broken, with the offending value
  std::string limit;  ///< the instrument or unit limit exceeded, empty if the rule is not a limit

  /// "<source>: <path>: <rule>[ (limit: <limit>)]".
  std::string Format(const std::string& source) const;
};

/// Thrown when a sequence is refused; what() lists every problem, one per line.
class SequenceError : public std::runtime_error {
 public:
  SequenceError(std::string source, std::vector<SequenceProblem> problems);
  const std::vector<SequenceProblem>& problems() const { return problems_; }
  const std::string& source() const { return source_; }

 private:
  std::string source_;
  std::vector<SequenceProblem> problems_;
};

/// Every problem of an already parsed sequence against `limits`; empty when it may run.
std::vector<SequenceProblem> ValidateSequence(const Sequence& sequence,
                                              const SequenceLimits& limits);

/// Parses and validates a sequence file in one pass: structural problems of the JSON (missing or
/// unknown keys, wrong types) and limit problems of every step that parsed, all together.
std::vector<SequenceProblem> CheckSequenceFile(const std::string& file_path,
                                               const SequenceLimits& limits);

/// Loads, parses and validates; throws SequenceError listing every problem.
Sequence LoadValidSequence(const std::string& file_path, const SequenceLimits& limits);

}  // namespace adahrs::calib
