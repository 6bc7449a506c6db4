// Fuzzes hil::ReadRecording on a compressed imu.csv.gz (recording_csv.h): gzip members, cut
// members and foreign bytes through hil::GzipReader.
#include "tests/fuzz/recording_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  adahrs::fuzz::ReadRecordingWithCsv("imu.csv.gz", "ads.csv", data, size);
  return 0;
}
