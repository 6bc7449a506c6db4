// A generic channel recording (docs/diagnose.md "Generic channel CSV"): any sensor logged
// elsewhere, one CSV with a header row (a time column, one or more outputs, a temperature,
// optional reference inputs), described by a JSON sidecar that names the columns and maps each to
// its physical unit: value = (raw, as a signed 16-bit integer when `int16`) * scale + offset.
// Time in s; temperature in degC; outputs and references in the units the sidecar names.
// Real logs: `skip_lines` banner lines before the header; time from a column or, with
// `time.rate_hz`, the data row's index over that rate; a row that does not parse (a cell that is
// not a finite number, too few cells) is counted and skipped, the first named in a note.
// Refused, naming the sidecar and its JSON path or the CSV, its line and column: a wrong format
// or format_version, a missing key or column, a time that does not increase, more than half the
// rows not parsing. Columns the sidecar does not name are ignored with a note. Rows are never
// interpolated: a gap longer than max_gap_s only splits segments.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace adahrs::diagnosis {

inline constexpr const char* kChannelCsvFormat = "adahrs-channel-csv";
inline constexpr int kChannelCsvFormatVersion = 1;
inline constexpr double kDefaultChannelSegment_s = 120.0;

class ChannelInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ChannelSeries {
  std::string name;
  std::string unit;
  double resolution =
      0.0;  ///< the output's step in its unit, when the sidecar gives it (0: unknown)
  std::vector<double> values;  ///< per row
};

struct ChannelRecording {
  std::string unit;     ///< the sidecar's name for the device
  std::string sidecar;  ///< path as given
  std::string csv;      ///< path of the CSV
  std::string sha256;   ///< of the CSV's bytes
  std::vector<double> t_s;
  std::vector<double> temp_c;
  std::vector<ChannelSeries> outputs;
  std::vector<ChannelSeries> references;
  double max_gap_s = 0.0;                       ///< a longer interval between rows splits segments
  double segment_s = kDefaultChannelSegment_s;  ///< segments are cut this long (`segment_s`)
  int skipped_rows = 0;  ///< data rows that did not parse, skipped (named in `notes`)
  std::vector<std::string> notes;
};

/// Reads the sidecar at `sidecar` and the CSV it names (relative to the sidecar's folder).
ChannelRecording ReadChannelRecording(const std::filesystem::path& sidecar);

}  // namespace adahrs::diagnosis
