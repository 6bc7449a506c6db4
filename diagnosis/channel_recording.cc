#include "diagnosis/channel_recording.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/sha256.h"

namespace adahrs::diagnosis {
namespace {

using nlohmann::json;

// One column of the CSV as the sidecar maps it.
struct ColumnMap {
  std::string column;
  double scale = 1.0;
  double offset = 0.0;
  bool int16 = false;
  int index = -1;  // in the header
};

class Sidecar {
 public:
  Sidecar(json j, std::string path) : j_(std::move(j)), path_(std::move(path)) {}

  [[noreturn]] void Fail(const std::string& where, const std::string& what) const {
    throw ChannelInputError(fmt::format("{}: {}: {}", path_, where, what));
  }
  const json& Require(const json& obj, const std::string& key, const std::string& where) const {
    if (!obj.is_object() || !obj.contains(key)) Fail(where, "missing key '" + key + "'");
    return obj[key];
  }
  std::string String(const json& obj, const std::string& key, const std::string& where) const {
    const json& v = Require(obj, key, where);
    if (!v.is_string()) Fail(where + "." + key, "expected a string");
    return v.get<std::string>();
  }
  double Number(const json& obj,
                const std::string& key,
                double fallback,
                const std::string& where) const {
    if (!obj.contains(key)) return fallback;
    if (!obj[key].is_number() || !std::isfinite(obj[key].get<double>()))
      Fail(where + "." + key, "expected a finite number");
    return obj[key].get<double>();
  }
  ColumnMap Column(const json& obj, const std::string& where) const {
    ColumnMap m;
    m.column = String(obj, "column", where);
    m.scale = Number(obj, "scale", 1.0, where);
    m.offset = Number(obj, "offset", 0.0, where);
    if (obj.contains("int16")) {
      if (!obj["int16"].is_boolean()) Fail(where + ".int16", "expected true or false");
      m.int16 = obj["int16"].get<bool>();
    }
    return m;
  }
  const json& root() const { return j_; }
  const std::string& path() const { return path_; }

 private:
  json j_;
  std::string path_;
};

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (char c : line) {
    if (c == ',') {
      cells.push_back(cell);
      cell.clear();
    } else if (c != '\r') {
      cell += c;
    }
  }
  cells.push_back(cell);
  for (std::string& s : cells) {
    const size_t a = s.find_first_not_of(" \t\"");
    const size_t b = s.find_last_not_of(" \t\"");
    s = a == std::string::npos ? "" : s.substr(a, b - a + 1);
  }
  return cells;
}

// A cell that does not parse: the row is skipped, not the recording refused (ReadRows).
class CellError : public ChannelInputError {
 public:
  using ChannelInputError::ChannelInputError;
};

double Cell(const std::vector<std::string>& cells,
            const ColumnMap& m,
            const std::string& csv,
            int line) {
  const std::string& text = cells[static_cast<size_t>(m.index)];
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) {
    throw CellError(fmt::format("{} line {} column {} ('{}'): '{}' is not a finite number",
                                csv,
                                line,
                                m.index + 1,
                                m.column,
                                text));
  }
  if (m.int16) {
    if (v != std::floor(v) || v < -32768.0 || v > 65535.0) {
      throw CellError(fmt::format("{} line {} column {} ('{}'): '{}' is not a 16-bit integer",
                                  csv,
                                  line,
                                  m.index + 1,
                                  m.column,
                                  text));
    }
    if (v > 32767.0) v -= 65536.0;
  }
  return v * m.scale + m.offset;
}

struct Layout {
  double rate_hz = 0.0;  ///< > 0: time is the data row's index over it, no time column
  ColumnMap time, temp;
  std::vector<ColumnMap> outputs, references;
};

void Locate(const std::vector<std::string>& header,
            ColumnMap* m,
            const std::string& csv,
            int header_line) {
  const auto it = std::find(header.begin(), header.end(), m->column);
  if (it == header.end())
    throw ChannelInputError(fmt::format("{} line {}: no column '{}'", csv, header_line, m->column));
  m->index = static_cast<int>(it - header.begin());
}

std::vector<ChannelSeries> Series(const Sidecar& sc,
                                  const std::string& key,
                                  bool required,
                                  std::vector<ColumnMap>* maps) {
  std::vector<ChannelSeries> out;
  if (!sc.root().contains(key)) {
    if (required) sc.Fail("$", "missing key '" + key + "'");
    return out;
  }
  const json& arr = sc.root()[key];
  if (!arr.is_array() || (required && arr.empty()))
    sc.Fail("$." + key, "expected a non-empty array");
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string where = fmt::format("$.{}[{}]", key, i);
    maps->push_back(sc.Column(arr[i], where));
    ChannelSeries s;
    s.name = sc.String(arr[i], "name", where);
    s.unit = sc.String(arr[i], "unit", where);
    s.resolution = std::abs(sc.Number(arr[i], "resolution", 0.0, where));
    out.push_back(std::move(s));
  }
  return out;
}

double TimeScale(const Sidecar& sc) {
  const std::string unit = sc.String(sc.root()["time"], "unit", "$.time");
  static const std::map<std::string, double> kScale = {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}};
  const auto it = kScale.find(unit);
  if (it == kScale.end()) sc.Fail("$.time.unit", "'" + unit + "' is not s, ms or us");
  return it->second;
}

// One data row parsed into `r`, or the reason it does not parse (line and column named).
bool ParseRow(const std::vector<std::string>& cells,
              const Layout& l,
              const std::string& csv,
              size_t header_size,
              int number,
              double t,
              ChannelRecording* r,
              std::string* why) {
  if (cells.size() < header_size) {
    *why = fmt::format(
        "{} line {}: {} cells where the header has {}", csv, number, cells.size(), header_size);
    return false;
  }
  try {
    if (l.rate_hz == 0.0) t = Cell(cells, l.time, csv, number);
    const double temp = Cell(cells, l.temp, csv, number);
    std::vector<double> out, ref;
    for (const ColumnMap& m : l.outputs) out.push_back(Cell(cells, m, csv, number));
    for (const ColumnMap& m : l.references) ref.push_back(Cell(cells, m, csv, number));
    if (!r->t_s.empty() && !(t > r->t_s.back())) {
      throw ChannelInputError(
          fmt::format("{} line {} column {} ('{}'): time {:.6g} s does not increase (previous "
                      "{:.6g} s)",
                      csv,
                      number,
                      l.time.index + 1,
                      l.time.column,
                      t,
                      r->t_s.back()));
    }
    r->t_s.push_back(t);
    r->temp_c.push_back(temp);
    for (size_t k = 0; k < out.size(); ++k) r->outputs[k].values.push_back(out[k]);
    for (size_t k = 0; k < ref.size(); ++k) r->references[k].values.push_back(ref[k]);
  } catch (const CellError& e) {
    *why = e.what();
    return false;
  }
  return true;
}

// Rows that do not parse are counted and skipped, the first named in a note; a recording where
// more than half do not parse is refused (the sidecar's mapping is then wrong, not the logger).
void ReadRows(std::ifstream& in,
              const Layout& l,
              const std::string& csv,
              size_t header_size,
              int first_line,
              ChannelRecording* r) {
  std::string line, first_bad;
  int number = first_line, data_rows = 0, bad = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    const double t = l.rate_hz > 0.0 ? data_rows / l.rate_hz : 0.0;  // row index / rate
    ++data_rows;
    std::string why;
    if (!ParseRow(SplitCsv(line), l, csv, header_size, number, t, r, &why)) {
      if (bad++ == 0) first_bad = why;
    }
  }
  r->skipped_rows = bad;
  if (bad > 0 && 2 * bad > data_rows) {
    throw ChannelInputError(fmt::format(
        "{}: {} of {} rows do not parse (the sidecar's columns may not be this file's); the first: "
        "{}",
        csv,
        bad,
        data_rows,
        first_bad));
  }
  if (r->t_s.size() < 2) {
    throw ChannelInputError(
        fmt::format("{}: fewer than 2 rows{}",
                    csv,
                    bad > 0 ? "; the first that does not parse: " + first_bad : ""));
  }
  if (bad > 0) {
    r->notes.push_back(fmt::format(
        "{}: {} of {} rows do not parse and were skipped (nothing interpolated); the first: {}",
        csv,
        bad,
        data_rows,
        first_bad));
  }
}

}  // namespace

ChannelRecording ReadChannelRecording(const std::filesystem::path& sidecar_path) {
  std::ifstream f(sidecar_path);
  if (!f) throw ChannelInputError(sidecar_path.string() + ": cannot be read");
  json j = json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw ChannelInputError(sidecar_path.string() + ": not a JSON object");
  const Sidecar sc(std::move(j), sidecar_path.string());
  if (sc.String(sc.root(), "format", "$") != kChannelCsvFormat) {
    sc.Fail("$.format", fmt::format("expected '{}'", kChannelCsvFormat));
  }
  const json& version = sc.Require(sc.root(), "format_version", "$");
  if (!version.is_number_integer() || version.get<int>() != kChannelCsvFormatVersion) {
    sc.Fail("$.format_version",
            fmt::format("{} is not a version this reader knows ({})",
                        version.dump(),
                        kChannelCsvFormatVersion));
  }
  ChannelRecording r;
  r.sidecar = sidecar_path.string();
  // The device's name: `device`, or `unit` as format version 1 first spelt it.
  r.unit = sc.String(sc.root(), sc.root().contains("device") ? "device" : "unit", "$");
  r.csv = (sidecar_path.parent_path() / sc.String(sc.root(), "csv", "$")).string();
  Layout l;
  const json& time = sc.Require(sc.root(), "time", "$");
  l.rate_hz = sc.Number(time, "rate_hz", 0.0, "$.time");
  if (l.rate_hz < 0.0) sc.Fail("$.time.rate_hz", "expected a rate above 0 Hz");
  if (l.rate_hz == 0.0) {
    l.time = sc.Column(time, "$.time");
    l.time.scale *= TimeScale(sc);
  } else if (time.contains("column")) {
    sc.Fail("$.time", "give either 'column' (with 'unit') or 'rate_hz', not both");
  }
  l.temp = sc.Column(sc.Require(sc.root(), "temperature", "$"), "$.temperature");
  r.outputs = Series(sc, "outputs", true, &l.outputs);
  r.references = Series(sc, "references", false, &l.references);
  r.max_gap_s = sc.Number(sc.root(), "max_gap_s", 0.0, "$");
  r.segment_s = sc.Number(sc.root(), "segment_s", r.segment_s, "$");
  if (!(r.segment_s > 0.0)) sc.Fail("$.segment_s", "expected a length above 0 s");
  const double skip = sc.Number(sc.root(), "skip_lines", 0.0, "$");
  if (skip < 0.0 || skip != std::floor(skip) || skip > 1e6)
    sc.Fail("$.skip_lines", "expected a whole number of lines >= 0");

  std::ifstream in(r.csv);
  if (!in) throw ChannelInputError(r.csv + ": cannot be read (named by " + r.sidecar + " $.csv)");
  std::string header_line;
  const int header_number = static_cast<int>(skip) + 1;
  for (int i = 0; i < header_number; ++i) {
    if (!std::getline(in, header_line)) {
      throw ChannelInputError(
          fmt::format("{}: ends before its header row (line {}, after skip_lines {})",
                      r.csv,
                      header_number,
                      static_cast<int>(skip)));
    }
  }
  if (header_line.rfind("\xEF\xBB\xBF", 0) == 0)
    header_line.erase(0, 3);  // a UTF-8 byte-order mark
  const std::vector<std::string> header = SplitCsv(header_line);
  std::vector<bool> used(header.size(), false);
  std::vector<ColumnMap*> named = {&l.temp};
  if (l.rate_hz == 0.0) named.push_back(&l.time);
  for (auto* group : {&l.outputs, &l.references}) {
    for (ColumnMap& m : *group) named.push_back(&m);
  }
  for (ColumnMap* m : named) {
    Locate(header, m, r.csv, header_number);
    used[static_cast<size_t>(m->index)] = true;
  }
  for (size_t i = 0; i < header.size(); ++i) {
    if (!used[i] && !header[i].empty())
      r.notes.push_back(
          fmt::format("{}: column '{}' ignored (not in the sidecar)", r.csv, header[i]));
  }
  if (l.rate_hz > 0.0) {
    r.notes.push_back(fmt::format(
        "{}: time is the data row's index over {:.6g} Hz (no time column)", r.csv, l.rate_hz));
  }
  ReadRows(in, l, r.csv, header.size(), header_number, &r);
  r.sha256 = common::FileSha256(r.csv);
  return r;
}

}  // namespace adahrs::diagnosis
