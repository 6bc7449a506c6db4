// Fuzzes calib::ReadJournal on journal.jsonl (the input). Refusal: calib::JournalError.
#include <cstddef>
#include <cstdint>

#include "calib/executor/journal.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  adahrs::fuzz::WriteScratchFile("journal.jsonl", data, size);
  try {
    (void)adahrs::calib::ReadJournal(adahrs::fuzz::ScratchDir());
  } catch (const adahrs::calib::JournalError&) {
  }
  return 0;
}
