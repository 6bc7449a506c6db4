#include "proving/studies/study_csv.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "proving/studies/study_results.h"

namespace adahrs::proving {

std::string StudyCsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::vector<std::string> StudyCsvSplit(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

std::string StudyCsvBool(bool b) { return b ? "1" : "0"; }

std::string ReadStudyText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void WriteStudyText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(file.string() + ": cannot be written");
}

void WriteStudyCsv(const std::filesystem::path& file,
                   const StudyMeta& meta,
                   const std::vector<StudyUnitResult>& results,
                   const StudyCsvLayout& layout) {
  std::string text = std::string(layout.header) + "\n";
  for (const StudyUnitResult& r : results) {
    for (size_t s = 0; s < meta.strategies.size(); ++s) {
      text += fmt::format("{},{},{},{},{},{}\n",
                          r.index,
                          r.serial,
                          r.draw_seed,
                          r.noise_seed,
                          StudyCsvField(meta.strategies[s].name),
                          layout.write_outcome(r.outcomes.at(s)));
    }
  }
  WriteStudyText(file, text);
}

std::vector<StudyUnitResult> ReadStudyCsv(const std::filesystem::path& file,
                                          const StudyMeta& meta,
                                          const StudyCsvLayout& layout) {
  std::istringstream in(ReadStudyText(file));
  std::string line;
  if (!std::getline(in, line) || line != layout.header) {
    throw std::runtime_error(file.string() + " line 1: not the " + layout.name + " header");
  }
  std::vector<StudyUnitResult> results;
  for (int n = 2; std::getline(in, line); ++n) {
    const std::vector<std::string> f = StudyCsvSplit(line);
    const size_t s = (n - 2) % meta.strategies.size();
    auto fail = [&](size_t column, const std::string& why) {
      throw std::runtime_error(file.string() + " line " + std::to_string(n) + " column " +
                               std::to_string(column + 1) + ": " + why);
    };
    if (f.size() != layout.columns)
      fail(0, "expected " + std::to_string(layout.columns) + " fields");
    if (f[4] != meta.strategies[s].name) fail(4, "expected strategy " + meta.strategies[s].name);
    try {
      if (s == 0) {
        StudyUnitResult r;
        r.index = std::stoi(f[0]);
        r.serial = f[1];
        r.draw_seed = std::stoull(f[2]);
        r.noise_seed = std::stoull(f[3]);
        results.push_back(r);
      } else if (std::stoi(f[0]) != results.back().index) {
        fail(0, "expected unit " + std::to_string(results.back().index));
      }
      results.back().outcomes.push_back(layout.read_outcome(f));
    } catch (const std::logic_error& e) {  // std::stoi and friends
      fail(0, std::string("not a number where one is expected (") + e.what() + ")");
    }
  }
  return results;
}

}  // namespace adahrs::proving
