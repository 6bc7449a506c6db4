// The JSON form of a sequence (docs/sequences.md gives the full grammar with an example):
//
//   {"format_version": 1, "name": "...", "description": "...", "unit_kind": "imu" | "ads",
//    "steps": [{"kind": "<kind>", "tag": 1…255 (optional), <the kind's fields>}, ...]}
//
// Fields carry their units in their names (`target_c`, `rate_max_dps`, `rate_ft_per_min`). The
// reader is strict (common/param_reader.h): a missing key, a wrong type, an unknown key (how
// a wrong unit suffix shows) is a problem naming the file and JSON path. It checks form only —
// limits are validation.h's — and it does not stop at the first bad step: every step is read and
// every structural problem reported. Saving writes the same form, so load → save → load is the
// identity; TAGs are saved as written (explicit ones only).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/sequence/sequence.h"
#include "calib/sequence/validation.h"

namespace adahrs::calib {

/// The outcome of reading a sequence document: the steps that could be read, where each came
/// from in the file, and every structural problem.
struct ParsedSequence {
  Sequence sequence;
  std::vector<size_t> file_step_index;  ///< index in the file's "steps" array of each step
  std::vector<SequenceProblem> problems;
};

/// Reads a parsed JSON document; `source` names it in messages (a file path).
ParsedSequence ParseSequence(const nlohmann::json& document, const std::string& source);

/// Reads a file; a file that cannot be opened or is not JSON gives one problem at "$".
ParsedSequence ParseSequenceFile(const std::string& file_path);

/// Reads a document and throws SequenceError listing every structural problem (no limit checks).
Sequence SequenceFromJson(const nlohmann::json& document, const std::string& source);

/// The JSON form, keys in the documented order.
nlohmann::ordered_json SequenceToJson(const Sequence& sequence);

/// Writes SequenceToJson with two-space indentation; throws std::runtime_error naming the file.
void SaveSequence(const Sequence& sequence, const std::string& file_path);

}  // namespace adahrs::calib
