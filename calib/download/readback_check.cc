#include "calib/download/readback_check.h"

#include <algorithm>

#include <fmt/format.h>

namespace adahrs::calib {

std::string ReadbackMismatch::Describe() const {
  if (written && read) {
    return fmt::format("word {}: wrote 0x{:04X}, read 0x{:04X}",
                       word_index,
                       static_cast<uint16_t>(*written),
                       static_cast<uint16_t>(*read));
  }
  return fmt::format("wrote {} words, read {}", written_words, read_words);
}

std::optional<ReadbackMismatch> CompareReadback(std::span<const int16_t> written,
                                                std::span<const int16_t> read) {
  const size_t common = std::min(written.size(), read.size());
  for (size_t i = 0; i < common; ++i) {
    if (written[i] != read[i])
      return ReadbackMismatch{i, written.size(), read.size(), written[i], read[i]};
  }
  if (written.size() != read.size()) {
    return ReadbackMismatch{common, written.size(), read.size(), std::nullopt, std::nullopt};
  }
  return std::nullopt;
}

}  // namespace adahrs::calib
