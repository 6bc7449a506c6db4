// results.csv of a study, for IMU and ADS studies alike: one row per unit and strategy in unit
// index order, the columns every study has first (unit_index, serial, draw_seed, noise_seed,
// strategy), then the unit kind's outcome columns (StudyCsvLayout). RFC 4180 quoting, no line
// breaks inside fields. Reading refuses a wrong header, a row of another width or strategy and a
// number that is not one, throwing std::runtime_error naming the file, line and column.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "proving/studies/imu_study.h"

namespace adahrs::proving {

struct StudyMeta;

/// A unit kind's results.csv: its header, its width, and its outcome columns (after `strategy`)
/// written and read back (`fields` holds every column of the row).
struct StudyCsvLayout {
  const char* header;
  size_t columns;
  const char* name;  ///< in messages: "study results", "ADS study results"
  std::function<std::string(const StrategyOutcome&)> write_outcome;  ///< "a,b,...", no newline
  std::function<StrategyOutcome(const std::vector<std::string>& fields)> read_outcome;
};

void WriteStudyCsv(const std::filesystem::path& file,
                   const StudyMeta& meta,
                   const std::vector<StudyUnitResult>& results,
                   const StudyCsvLayout& layout);
std::vector<StudyUnitResult> ReadStudyCsv(const std::filesystem::path& file,
                                          const StudyMeta& meta,
                                          const StudyCsvLayout& layout);

/// A CSV field, quoted when it holds a comma, quote or line break; a line split back into fields.
std::string StudyCsvField(const std::string& text);
std::vector<std::string> StudyCsvSplit(const std::string& line);
/// "1" or "0".
std::string StudyCsvBool(bool b);
std::string ReadStudyText(const std::filesystem::path& file);
void WriteStudyText(const std::filesystem::path& file, const std::string& text);

}  // namespace adahrs::proving
