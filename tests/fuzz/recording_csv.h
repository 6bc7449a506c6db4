// The recording reader's CSV targets (recording_imu_csv, recording_ads_csv): the input is one CSV
// file of a run directory whose meta.json and other CSV (a header) come from tests/fuzz/fixtures.
// Refusal: hil::RecordingError. Odd-sized inputs are read with allow_truncated_tail.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "hil/recording/recording_reader.h"
#include "tests/fuzz/fuzz_support.h"

namespace adahrs::fuzz {

inline void ReadRecordingWithCsv(const std::string& fuzzed_csv,
                                 const std::string& fixture_csv,
                                 const uint8_t* data,
                                 size_t size) {
  static const bool fixtures = [&] {
    CopyToScratch(ADAHRS_FUZZ_FIXTURES "/meta.json", "meta.json");
    CopyToScratch(ADAHRS_FUZZ_FIXTURES "/" + fixture_csv, fixture_csv);
    return true;
  }();
  (void)fixtures;
  WriteScratchFile(fuzzed_csv, data, size);
  try {
    hil::ReadRecording(ScratchDir(), {.allow_truncated_tail = size % 2 == 1});
  } catch (const hil::RecordingError&) {
  }
}

}  // namespace adahrs::fuzz
