#include "calib/executor/journal.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/printable_text.h"

namespace adahrs::calib {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& what) {
  throw JournalError(path.string() + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

Journal::Journal(const std::filesystem::path& run_dir) : path_(run_dir / kJournalName) {
  file_ = std::fopen(path_.c_str(), "a");
  if (file_ == nullptr) Fail(path_, "cannot open for appending");
}

Journal::~Journal() { std::fclose(file_); }

void Journal::Append(const JournalEvent& event) {
  const std::string line = ToJson(event).dump() + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0) {
    Fail(path_, "write failed");
  }
}

void Journal::Sync() {
  if (std::fflush(file_) != 0) Fail(path_, "flush failed");
  if (::fsync(::fileno(file_)) != 0) Fail(path_, "fsync failed");
}

JournalContents ReadJournal(const std::filesystem::path& run_dir) {
  const std::filesystem::path path = run_dir / kJournalName;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw JournalError(path.string() + ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  JournalContents contents;
  size_t start = 0;
  int line = 0;
  while (start < text.size()) {
    ++line;
    const size_t end = text.find('\n', start);
    if (end == std::string::npos) {
      contents.torn_lines = 1;  // no newline: the write was cut short
      break;
    }
    const std::string_view item(text.data() + start, end - start);
    start = end + 1;
    nlohmann::json event;
    try {
      event = nlohmann::json::parse(item);
    } catch (const nlohmann::json::parse_error& e) {
      throw JournalError(path.string() + ":" + std::to_string(line) + ": not JSON (byte " +
                         std::to_string(e.byte) + ")");
    } catch (const nlohmann::json::exception& e) {  // a number beyond double's range
      throw JournalError(path.string() + ":" + std::to_string(line) +
                         ": not JSON: " + common::PrintableText(e.what()));
    }
    contents.events.push_back(
        JournalEventFromJson(event, path.string() + ":" + std::to_string(line)));
  }
  return contents;
}

}  // namespace adahrs::calib
