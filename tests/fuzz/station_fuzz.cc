// Fuzzes hil::Station::Load on a station file (the input). Refusal: common::ParamError.
#include <cstddef>
#include <cstdint>

#include "common/param_reader.h"
#include "hil/station.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto path = adahrs::fuzz::WriteScratchFile("station.json", data, size).string();
  try {
    (void)adahrs::hil::Station::Load(path);
  } catch (const adahrs::common::ParamError&) {
  }
  return 0;
}
