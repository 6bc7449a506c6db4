// Refusing invalid sequences before anything moves. Every problem is collected, none stops the
// check: each names the file, the JSON path of the offending value, the rule broken and, when a
// limit is exceeded, the instrument or unit limit with its value (SequenceLimits). Rules cover the
// structure (step kinds per unit kind), TAGs (1…255, explicit ones unique, enough free ones),
// orientations (11, 12, 21, 22, 31, 32), packet counts and log durations, gyro and cross-axis
// rates and table accelerations, chamber set points and F4 profiles, ADTS altitudes and airspeeds
// against the unit's pressure limits and slew rates, and prompt text.
// Units as the fields name them (deg/s, deg/s^2, degC, ft, kt, s).
// Every rule with its default limit: docs/sequences.md ("Validation").
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
