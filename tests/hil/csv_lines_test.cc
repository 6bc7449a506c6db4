#include "hil/recording/csv_lines.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <ranges>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

std::filesystem::path WriteFile(const std::string& name, const std::string& bytes) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("adahrs_csv_lines_" + name + "_" + std::to_string(::getpid()));
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::vector<std::pair<std::string, bool>> ReadLines(const std::filesystem::path& path) {
  CsvLines lines(path);
  std::vector<std::pair<std::string, bool>> out;
  std::string_view line;
  bool complete = false;
  while (lines.Next(line, complete)) out.emplace_back(std::string(line), complete);
  return out;
}

// Lines that straddle the 1 MiB read blocks, one longer than a block, an empty one, and a last
// line without its LF (a torn row) come back exactly as written.
TEST(CsvLines, GivesEveryLineAcrossBlocksAndFlagsTheTornLast) {
  std::vector<std::string> written;
  for (int i = 0; i < 40000; ++i) written.push_back("row " + std::to_string(i * 7919) + ",x,y");
  written.push_back(std::string(3 << 20, 'z'));
  written.push_back("");
  written.push_back("after the long line");
  std::string bytes;
  for (const std::string& line : written) bytes += line + "\n";
  bytes += "torn,row";
  const auto path = WriteFile("blocks", bytes);
  const auto lines = ReadLines(path);
  ASSERT_EQ(lines.size(), written.size() + 1);
  for (size_t i = 0; i < written.size(); ++i) {
    ASSERT_EQ(lines[i].first, written[i]) << "line " << i + 1;
    ASSERT_TRUE(lines[i].second) << "line " << i + 1;
  }
  EXPECT_EQ(lines.back().first, "torn,row");
  EXPECT_FALSE(lines.back().second);
  std::filesystem::remove(path);
}

TEST(CsvLines, EmptyFileHasNoLinesAndAMissingOneNamesItsPath) {
  const auto path = WriteFile("empty", "");
  EXPECT_TRUE(ReadLines(path).empty());
  std::filesystem::remove(path);
  try {
    CsvLines lines(path);
    FAIL() << "opened a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

// SplitCells against the standard library's split view, on lines of every length up to 70 bytes
// (the 16-byte blocks and the bytes after them), commas anywhere: leading, trailing, repeated.
TEST(SplitCells, AgreesWithTheStandardSplitView) {
  std::mt19937 random(5);
  std::vector<std::string_view> cells{"left over"};
  for (int round = 0; round < 20000; ++round) {
    std::string line(static_cast<size_t>(round % 71), 'x');
    for (char& c : line) {
      const auto draw = random() % 8;
      c = draw == 0 ? ',' : static_cast<char>('0' + draw);
    }
    std::vector<std::string> expected;
    for (const auto cell : std::views::split(line, ',')) {
      expected.emplace_back(cell.begin(), cell.end());
    }
    if (line.empty()) expected.emplace_back();  // the view has no element for an empty range
    SplitCells(line, cells);
    ASSERT_EQ(std::vector<std::string>(cells.begin(), cells.end()), expected) << "'" << line << "'";
  }
}

}  // namespace
}  // namespace adahrs::hil
