#include "hil/recording/recording_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "common/printable_text.h"
#include "hil/recording/csv_lines.h"
#include "hil/recording/decimal_parse.h"
#include "hil/recording/frame_count.h"
#include "hil/recording/recording_files.h"

namespace adahrs::hil {

using common::PrintableText;

namespace {

std::vector<std::string> SplitHeader(std::string_view header) {
  std::vector<std::string> names;
  size_t start = 0;
  while (start <= header.size()) {
    const size_t comma = header.find(',', start);
    const size_t end = comma == std::string_view::npos ? header.size() : comma;
    names.emplace_back(header.substr(start, end - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return names;
}

// One CSV file being parsed: knows its path, the current line and the column names, so every
// error can say where it happened.
class CsvCursor {
 public:
  // Reads the header and maps the format's columns onto the file's: a format column the file
  // lacks, or a name the header repeats, is refused; a column the format does not know is
  // ignored and named in `notes`; one of the latest version's columns in an older version's file
  // (`latest_header`) says meta.json's version is wrong and is refused.
  CsvCursor(const std::filesystem::path& path,
            std::string_view header,
            std::string_view latest_header,
            int version,
            std::vector<std::string>* notes)
      : path_(path), names_(SplitHeader(header)) {
    try {
      lines_ = std::make_unique<CsvLines>(path_);
    } catch (const std::runtime_error&) {
      throw RecordingError(path_.string() + ": cannot open for reading");
    }
    std::string_view first;
    bool complete = false;
    if (!NextLine(first, complete)) {
      throw RecordingError(path_.string() + ": empty file, no header");
    }
    line_ = 1;
    if (first == header) {
      file_columns_ = names_.size();
      for (size_t i = 0; i < names_.size(); ++i) column_of_.push_back(i);
      return;
    }
    MapColumns(SplitHeader(first), SplitHeader(latest_header), version, notes);
  }

  int line() const { return static_cast<int>(line_); }  ///< 1-based line of the current row

  // Reads the next row's cells; false at the end. A last line without its newline is truncated.
  bool Next(bool allow_truncated_tail, int& truncated) {
    std::string_view text;
    bool complete = false;
    if (!NextLine(text, complete)) return false;
    ++line_;
    SplitCells(text, cells_);
    if (!complete && allow_truncated_tail) {
      ++truncated;
      return false;
    }
    if (!complete && lines_->stream_truncated()) {
      throw RecordingError(Where() +
                           ": truncated: the file ends inside a gzip member (a crash while "
                           "writing); the rows before this line are complete");
    }
    if (!complete || cells_.size() != file_columns_) {
      throw RecordingError(Where() + (complete ? "" : " (last line, no newline: truncated?)") +
                           ": " + std::to_string(cells_.size()) + " columns, expected " +
                           std::to_string(file_columns_) + " (as the header)");
    }
    return true;
  }

  double Real(size_t column) const {
    double v = 0.0;
    const std::string_view cell = cells_[column_of_[column]];
    if (!ParseDecimalReal(cell, v) || !std::isfinite(v)) [[unlikely]] {
      NotANumber(column, cell);
    }
    return v;
  }

  template <typename Int>
  Int Integer(size_t column) const {
    long long v = 0;
    const std::string_view cell = cells_[column_of_[column]];
    if (!ParseDecimalInteger(cell, v) ||
        v < static_cast<long long>(std::numeric_limits<Int>::min()) ||
        v > static_cast<long long>(std::numeric_limits<Int>::max())) [[unlikely]] {
      NotAnInteger(column,
                   cell,
                   static_cast<long long>(std::numeric_limits<Int>::min()),
                   static_cast<long long>(std::numeric_limits<Int>::max()));
    }
    return static_cast<Int>(v);
  }

  // The errors of Real and Integer, out of the parsing path.
  [[noreturn, gnu::cold, gnu::noinline]] void NotANumber(size_t column,
                                                         std::string_view cell) const {
    throw RecordingError(Where(column) + ": '" + PrintableText(cell) + "' is not a finite number");
  }
  [[noreturn, gnu::cold, gnu::noinline]] void NotAnInteger(size_t column,
                                                           std::string_view cell,
                                                           long long min,
                                                           long long max) const {
    throw RecordingError(Where(column) + ": '" + PrintableText(cell) + "' is not an integer in [" +
                         std::to_string(min) + ", " + std::to_string(max) + "]");
  }

  bool Empty(size_t column) const { return cells_[column_of_[column]].empty(); }

  // The frame index in `frame_column`, checked against the sample time in `time_column`
  // (frame * 10 ms, written to the 10 ms digit).
  int64_t Frame(size_t frame_column, size_t time_column) const {
    const auto frame = Integer<int64_t>(frame_column);
    if (frame < 0)
      throw RecordingError(Where(frame_column) + ": frame " + std::to_string(frame) +
                           " is negative");
    const double t_sample_s = Real(time_column);
    if (std::abs(t_sample_s - SampleTimeS(frame)) > 0.5 * kUnitFramePeriod_s) {
      throw RecordingError(Where(time_column) + ": " + std::to_string(t_sample_s) +
                           " s is not frame " + std::to_string(frame) + " times 10 ms");
    }
    return frame;
  }

  // The compensated cells [first, last] of a version-2 row: all empty in raw mode (false), all
  // present otherwise (true); a mixture is an error naming the first offending column.
  bool CompensatedPresent(size_t first, size_t last, unsigned mode) const {
    for (size_t c = first; c <= last; ++c) {
      if (Empty(c) != (mode == 0)) {
        throw RecordingError(Where(c) + (mode == 0 ? ": not empty, but mode is 0 (raw)"
                                                   : ": empty, but mode is " +
                                                         std::to_string(mode) + " (compensated)"));
      }
    }
    return mode != 0;
  }

  std::string_view Text(size_t column) const {
    if (cells_[column_of_[column]].empty()) throw RecordingError(Where(column) + ": empty");
    return cells_[column_of_[column]];
  }

 private:
  // The next line; corrupt compressed data is refused as a RecordingError naming the file.
  bool NextLine(std::string_view& text, bool& complete) {
    try {
      return lines_->Next(text, complete);
    } catch (const std::runtime_error& e) {
      throw RecordingError(std::string(e.what()) + " (after line " + std::to_string(line_) + ")");
    }
  }
  std::string Where() const { return path_.string() + ":" + std::to_string(line_); }
  std::string Where(size_t column) const {
    return Where() + ": column " + std::to_string(column_of_[column] + 1) + " (" + names_[column] +
           ")";
  }

  void MapColumns(const std::vector<std::string>& file_names,
                  const std::vector<std::string>& latest_names,
                  int version,
                  std::vector<std::string>* notes) {
    const std::string format =
        " (recording format version " + std::to_string(version) + ", as meta.json says)";
    for (size_t i = 0; i < file_names.size(); ++i) {
      for (size_t j = 0; j < i; ++j) {
        if (file_names[j] == file_names[i]) {
          throw RecordingError(path_.string() + ":1: column " + std::to_string(i + 1) + " '" +
                               PrintableText(file_names[i]) + "' repeats column " +
                               std::to_string(j + 1));
        }
      }
    }
    for (const std::string& name : names_) {
      const auto it = std::find(file_names.begin(), file_names.end(), name);
      if (it == file_names.end()) {
        throw RecordingError(path_.string() + ":1: column '" + name + "' is missing" + format);
      }
      column_of_.push_back(static_cast<size_t>(it - file_names.begin()));
    }
    for (size_t i = 0; i < file_names.size(); ++i) {
      if (std::find(names_.begin(), names_.end(), file_names[i]) != names_.end()) continue;
      if (std::find(latest_names.begin(), latest_names.end(), file_names[i]) !=
          latest_names.end()) {
        throw RecordingError(path_.string() + ":1: column " + std::to_string(i + 1) + " '" +
                             PrintableText(file_names[i]) +
                             "' belongs to a later recording format version, but meta.json "
                             "says version " +
                             std::to_string(version));
      }
      notes->push_back(path_.string() + ": column " + std::to_string(i + 1) + " '" +
                       PrintableText(file_names[i]) + "' is not in the recording format" + format +
                       "; ignored");
    }
    file_columns_ = file_names.size();
  }

  std::filesystem::path path_;
  std::vector<std::string> names_;  ///< the format's columns, in the format's order
  std::vector<size_t> column_of_;   ///< file column of each format column
  size_t file_columns_ = 0;
  std::unique_ptr<CsvLines> lines_;
  std::vector<std::string_view> cells_;  ///< views into lines_' buffer, valid until Next

  long line_ = 0;
};

}  // namespace

Recording ReadRecording(const std::filesystem::path& run_dir, const ReadOptions& options) {
  Recording rows;
  Recording rec =
      StreamRecording(run_dir,
                      {[&](ImuRecordRow&& r, int) { rows.imu.push_back(std::move(r)); },
                       [&](AdsRecordRow&& r, int) { rows.ads.push_back(std::move(r)); }},
                      options);
  rec.imu = std::move(rows.imu);
  rec.ads = std::move(rows.ads);
  return rec;
}

Recording ReadRecordingMeta(const std::filesystem::path& run_dir) {
  Recording rec;
  const std::filesystem::path meta_path = run_dir / kMetaJsonName;
  std::ifstream meta_in(meta_path);
  if (!meta_in) throw RecordingError(meta_path.string() + ": cannot open for reading");
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(meta_in);
  } catch (const nlohmann::json::parse_error& e) {
    throw RecordingError(meta_path.string() + ": not valid JSON at byte " + std::to_string(e.byte));
  } catch (const nlohmann::json::exception& e) {  // a number beyond double's range (1e400)
    throw RecordingError(meta_path.string() + ": not valid JSON: " + e.what());
  }
  if (!meta.is_object() || !meta.contains("format_version")) {
    throw RecordingError(meta_path.string() + ": $.format_version missing");
  }
  const nlohmann::json& v = meta.at("format_version");
  if (!v.is_number_integer()) {
    throw RecordingError(meta_path.string() + ": $.format_version is " + v.dump() +
                         ", not an integer");
  }
  // Read wide, so 4294967298 is refused as itself instead of wrapping to 2.
  const int64_t version =
      v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX)
          ? INT64_MAX
          : v.get<int64_t>();
  if (version < kOldestReadableFormatVersion || version > kRecordingFormatVersion) {
    throw RecordingError(meta_path.string() + ": $.format_version is " + v.dump() +
                         "; this software reads versions " +
                         std::to_string(kOldestReadableFormatVersion) + " to " +
                         std::to_string(kRecordingFormatVersion));
  }
  rec.meta = RecordingMeta::FromJson(meta, meta_path.string());
  return rec;
}

namespace {

// Per unit, rows come in the order they arrived: a row of a unit meta.json does not list (when it
// lists serials), a negative step, time going back, or the unit's previous row again (same time,
// counter and raw readings: a copy, not a burst of packets sharing an arrival time) is refused,
// naming the file and line. Read twice, a row would count twice in every fit and narrow its
// standard errors.
class RowOrder {
 public:
  RowOrder(const RecordingMeta& meta, std::filesystem::path file)
      : file_(std::move(file)), sample_times_(meta, file_) {
    for (const RecordingUnit& u : meta.units) {
      if (!u.serial.empty()) last_[u.serial];
    }
    listed_ = !last_.empty();
  }

  // Checks the row and returns its frame: `frame` as the file gives it (from version 3: it must
  // not go back and must be `seq` modulo 256), or counted from the counter and the arrival time
  // (-1, older versions) as the writer counts it.
  int64_t Check(const std::string& unit,
                int step,
                double t_s,
                uint32_t seq,
                uint64_t raw,
                int64_t frame,
                int line) {
    auto it = last_.find(unit);
    if (it == last_.end()) {
      if (listed_) Fail(line, "unit '" + unit + "' is not listed in meta.json $.units");
      it = last_.emplace(unit, Last{}).first;
    }
    if (step < 0) Fail(line, "unit " + unit + " step " + std::to_string(step) + " is negative");
    Last& l = it->second;
    if (l.seen && t_s < l.t_s) {
      Fail(line, Format("unit %s t_s %.6f s goes back from %.6f s", unit, t_s, l.t_s));
    }
    if (l.seen && t_s == l.t_s && seq == l.seq && raw == l.raw) {
      Fail(line, Format("unit %s repeats its previous row (seq %u, t_s %.6f s)", unit, seq, t_s));
    }
    if (frame < 0) {
      frame = l.frames.Next(seq, t_s);
    } else {
      if ((frame - static_cast<int64_t>(seq)) % kPacketCounterModulo != 0) {
        Fail(line,
             "unit " + unit + " frame " + std::to_string(frame) + " is not its seq " +
                 std::to_string(seq) + " modulo 256");
      }
      if (l.seen && frame < l.frames.last()->frame) {
        Fail(line,
             "unit " + unit + " frame " + std::to_string(frame) + " goes back from " +
                 std::to_string(l.frames.last()->frame));
      }
      l.frames = FrameCounter(FrameState{frame, seq, t_s});
    }
    l.seen = true;
    l.t_s = t_s;
    l.seq = seq;
    l.raw = raw;
    sample_times_.Row(unit, frame, t_s, line);
    return frame;
  }

  std::vector<SampleTimeDefect> Defects() const { return sample_times_.Defects(); }

 private:
  struct Last {
    bool seen = false;
    double t_s = 0.0;
    uint32_t seq = 0;
    uint64_t raw = 0;
    FrameCounter frames;
  };
  template <typename... Args>
  static std::string Format(const char* format, const std::string& unit, Args... args) {
    char text[256];
    std::snprintf(text, sizeof text, format, unit.c_str(), args...);
    return text;
  }
  [[noreturn]] void Fail(int line, const std::string& what) const {
    throw RecordingError(file_.string() + ":" + std::to_string(line) + ": " + PrintableText(what));
  }
  std::filesystem::path file_;
  std::map<std::string, Last> last_;
  bool listed_ = false;
  SampleTimeCheck sample_times_;
};

// The raw readings of a row folded into one word: equal for a copied row, all but never for two
// packets (the gyro and bridge counts carry noise).
uint64_t RawWord(const ImuRecordRow& r) {
  uint64_t w = 1469598103934665603ull;
  const auto mix = [&w](uint64_t v) { w = (w ^ v) * 1099511628211ull; };
  for (uint16_t t : r.accel_ticks) mix(t);
  for (int32_t g : r.gyro_cnt) mix(static_cast<uint32_t>(g));
  for (uint16_t t : r.temp_cnt) mix(t);
  return w;
}

uint64_t RawWord(const AdsRecordRow& r) {
  uint64_t w = 1469598103934665603ull;
  const auto mix = [&w](int32_t v) { w = (w ^ static_cast<uint32_t>(v)) * 1099511628211ull; };
  for (int32_t c : {r.ps_cnt, r.pt_cnt, r.ps_temp_cnt, r.pt_temp_cnt, r.oat_cnt}) mix(c);
  return w;
}

// The stored form of `csv_name` (plain or compressed); both forms present is refused.
std::filesystem::path StoredPath(const std::filesystem::path& run_dir, std::string_view csv_name) {
  try {
    return StoredCsvPath(run_dir, csv_name);
  } catch (const std::runtime_error& e) {
    throw RecordingError(e.what());
  }
}

}  // namespace

Recording StreamRecording(const std::filesystem::path& run_dir,
                          const RowSinks& sinks,
                          const ReadOptions& options) {
  Recording rec = ReadRecordingMeta(run_dir);
  const int version = rec.meta.format_version;
  const bool v2 = version >= 2;
  const bool v3 = version >= 3;
  const bool v4 = version >= 4;
  const std::string_view imu_header = v3 ? kImuCsvHeader : v2 ? kImuCsvHeaderV2 : kImuCsvHeaderV1;
  const std::string_view ads_header = v4   ? kAdsCsvHeader
                                      : v3 ? kAdsCsvHeaderV3
                                      : v2 ? kAdsCsvHeaderV2
                                           : kAdsCsvHeaderV1;

  const std::filesystem::path imu_path = StoredPath(run_dir, kImuCsvName);
  const std::filesystem::path ads_path = StoredPath(run_dir, kAdsCsvName);
  CsvCursor imu(imu_path, imu_header, kImuCsvHeader, version, &rec.notes);
  RowOrder imu_order(rec.meta, imu_path);
  while (imu.Next(options.allow_truncated_tail, rec.truncated_lines)) {
    ImuRecordRow r;
    r.t_s = imu.Real(0);
    r.unit = imu.Text(1);
    r.seq = imu.Integer<uint32_t>(2);
    r.step = imu.Integer<int>(3);
    r.tag = imu.Integer<uint8_t>(4);
    r.orientation = imu.Integer<int>(5);
    r.chamber_c = imu.Real(6);
    r.table_rate_dps = imu.Real(7);
    for (size_t i = 0; i < 12; ++i) r.accel_ticks[i] = imu.Integer<uint16_t>(8 + i);
    for (size_t i = 0; i < 3; ++i) r.gyro_cnt[i] = imu.Integer<int32_t>(20 + i);
    for (size_t i = 0; i < 3; ++i) r.temp_cnt[i] = imu.Integer<uint16_t>(23 + i);
    if (v2) {
      r.mode = imu.Integer<uint8_t>(26);
      if (imu.CompensatedPresent(27, 36, r.mode)) {
        std::array<double, 9> comp{};
        for (size_t i = 0; i < 9; ++i) comp[i] = imu.Real(27 + i);
        r.comp = comp;
        r.comp_flags = imu.Integer<uint32_t>(36);
      }
    }
    r.frame = imu_order.Check(
        r.unit, r.step, r.t_s, r.seq, RawWord(r), v3 ? imu.Frame(37, 38) : -1, imu.line());
    if (sinks.imu) sinks.imu(std::move(r), imu.line());
  }
  CsvCursor ads(ads_path, ads_header, kAdsCsvHeader, version, &rec.notes);
  RowOrder ads_order(rec.meta, ads_path);
  while (ads.Next(options.allow_truncated_tail, rec.truncated_lines)) {
    AdsRecordRow r;
    r.t_s = ads.Real(0);
    r.unit = ads.Text(1);
    r.seq = ads.Integer<uint32_t>(2);
    r.step = ads.Integer<int>(3);
    r.tag = ads.Integer<uint8_t>(4);
    r.chamber_c = ads.Real(5);
    r.ps_ref_pa = ads.Real(6);
    r.qc_ref_pa = ads.Real(7);
    r.ps_cnt = ads.Integer<int32_t>(8);
    r.pt_cnt = ads.Integer<int32_t>(9);
    r.ps_temp_cnt = ads.Integer<int32_t>(10);
    r.pt_temp_cnt = ads.Integer<int32_t>(11);
    r.oat_cnt = ads.Integer<int32_t>(12);
    if (v2) {
      r.mode = ads.Integer<uint8_t>(13);
      if (ads.CompensatedPresent(14, 16, r.mode)) {
        r.alt_ft = ads.Real(14);
        r.cas_kt = ads.Real(15);
        r.comp_flags = ads.Integer<uint32_t>(16);
      }
    }
    r.frame = ads_order.Check(
        r.unit, r.step, r.t_s, r.seq, RawWord(r), v3 ? ads.Frame(17, 18) : -1, ads.line());
    if (sinks.ads) sinks.ads(std::move(r), ads.line());
  }
  for (const RowOrder* order : {&imu_order, &ads_order}) {
    for (SampleTimeDefect& d : order->Defects()) rec.sample_time_defects.push_back(std::move(d));
  }
  return rec;
}

bool IsRejected(const Recording& recording, double t_s) {
  for (const RejectedInterval& r : recording.meta.rejected_intervals) {
    if (t_s >= r.t_start_s && t_s <= r.t_end_s) return true;
  }
  return false;
}

}  // namespace adahrs::hil
