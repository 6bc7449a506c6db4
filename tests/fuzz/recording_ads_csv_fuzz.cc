// Fuzzes hil::ReadRecording on ads.csv (recording_csv.h).
#include "tests/fuzz/recording_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  adahrs::fuzz::ReadRecordingWithCsv("ads.csv", "imu.csv", data, size);
  return 0;
}
