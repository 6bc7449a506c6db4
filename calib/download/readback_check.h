// Bit-for-bit comparison of a block as written with the block as the unit reads it back: the
// download commits nothing unless every block compares equal (docs/download.md).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace adahrs::calib {

struct ReadbackMismatch {
  size_t word_index = 0;  ///< first differing word (== the shorter length if lengths differ)
  size_t written_words = 0;
  size_t read_words = 0;
  std::optional<int16_t> written;  ///< the word written there (none past the end)
  std::optional<int16_t> read;     ///< the word read back there (none past the end)

  /// "word 7: wrote 0x1234, read 0x1236" or "wrote 14 words, read 13".
  std::string Describe() const;
};

/// The first difference between `written` and `read`, or nothing when they are identical.
std::optional<ReadbackMismatch> CompareReadback(std::span<const int16_t> written,
                                                std::span<const int16_t> read);

}  // namespace adahrs::calib
