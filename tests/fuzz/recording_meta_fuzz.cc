// Fuzzes hil::ReadRecordingMeta on meta.json (the input). Refusal: hil::RecordingError.
#include <cstddef>
#include <cstdint>

#include "hil/recording/recording_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  adahrs::fuzz::WriteScratchFile("meta.json", data, size);
  try {
    adahrs::hil::ReadRecordingMeta(adahrs::fuzz::ScratchDir());
  } catch (const adahrs::hil::RecordingError&) {
  }
  return 0;
}
