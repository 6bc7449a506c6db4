// Fuzzes calib::ReadConstantsFile on constants.json (the input), then writes back what it
// accepted (ToJson must not refuse a file the reader accepted). Refusal: calib::ConstantsFileError.
#include <cstddef>
#include <cstdint>

#include "calib/constants/constants_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto path = adahrs::fuzz::WriteScratchFile("constants.json", data, size);
  adahrs::calib::ConstantsFile file;
  try {
    file = adahrs::calib::ReadConstantsFile(path);
  } catch (const adahrs::calib::ConstantsFileError&) {
    return 0;
  }
  (void)adahrs::calib::ToJson(file);
  return 0;
}
