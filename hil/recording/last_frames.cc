#include "hil/recording/last_frames.h"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "common/printable_text.h"
#include "hil/recording/csv_lines.h"

namespace adahrs::hil {
namespace {

std::vector<std::string_view> Cells(std::string_view line) {
  std::vector<std::string_view> cells;
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

// Cell `index` of `line` (empty past the last).
std::string_view Cell(std::string_view line, size_t index) {
  size_t start = 0;
  for (size_t i = 0; i < index; ++i) {
    start = line.find(',', start);
    if (start == std::string_view::npos) return {};
    ++start;
  }
  return line.substr(start, line.find(',', start) - start);
}

struct LastLine {
  std::string text;
  long number = 0;
};

template <typename T>
T Parse(const std::filesystem::path& path,
        const LastLine& line,
        const std::vector<std::string_view>& cells,
        size_t column,
        std::string_view name) {
  T value{};
  const std::string_view cell = column < cells.size() ? cells[column] : std::string_view();
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || ec != std::errc() || end != cell.data() + cell.size()) {
    throw std::runtime_error(path.string() + ":" + std::to_string(line.number) + ": column " +
                             std::to_string(column + 1) + " (" + std::string(name) + ") '" +
                             common::PrintableText(cell) + "' is not a number");
  }
  return value;
}

}  // namespace

std::map<std::string, FrameState> LastFrames(const std::filesystem::path& csv_path) {
  std::map<std::string, FrameState> frames;
  if (!std::filesystem::exists(csv_path)) return frames;
  CsvLines lines(csv_path);
  std::string_view line;
  bool complete = false;
  if (!lines.Next(line, complete)) return frames;
  const std::vector<std::string_view> header_cells = Cells(line);
  const std::vector<std::string> header(header_cells.begin(), header_cells.end());
  const auto column = [&](std::string_view name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const size_t t_s = column("t_s"), unit = column("unit"), seq = column("seq");
  const size_t frame = column("frame");
  if (std::max({t_s, unit, seq, frame}) >= header.size()) return frames;

  std::map<std::string, LastLine, std::less<>> last;
  for (long number = 2; lines.Next(line, complete); ++number) {
    if (!complete) break;
    const std::string_view serial = Cell(line, unit);
    auto it = last.find(serial);
    if (it == last.end()) it = last.emplace(std::string(serial), LastLine{}).first;
    LastLine& l = it->second;
    l.text.assign(line);
    l.number = number;
  }
  for (const auto& [serial, l] : last) {
    const std::vector<std::string_view> cells = Cells(l.text);
    frames[serial] = FrameState{Parse<int64_t>(csv_path, l, cells, frame, "frame"),
                                Parse<uint32_t>(csv_path, l, cells, seq, "seq"),
                                Parse<double>(csv_path, l, cells, t_s, "t_s")};
  }
  return frames;
}

}  // namespace adahrs::hil
