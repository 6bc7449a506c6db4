// Fuzzes the sequence file reader as `adahrs sequence check` and `adahrs run` use it:
// calib::CheckSequenceFile (every problem), then calib::LoadValidSequence (throws on any) and
// the expanded plan of a valid one.
// Refusal: calib::SequenceError; problems are data.
#include <cstddef>
#include <cstdint>

#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_json.h"
#include "calib/sequence/validation.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto path = adahrs::fuzz::WriteScratchFile("sequence.json", data, size).string();
  const adahrs::calib::SequenceLimits limits;
  (void)adahrs::calib::CheckSequenceFile(path, limits);
  try {
    auto sequence = adahrs::calib::LoadValidSequence(path, limits);
    (void)adahrs::calib::SequenceToJson(sequence);
    (void)adahrs::calib::ExpandSequence(sequence, limits);
  } catch (const adahrs::calib::SequenceError&) {
  }
  return 0;
}
