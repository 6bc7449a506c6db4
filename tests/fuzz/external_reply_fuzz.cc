// Fuzzes calib::CheckExternalReply on an external strategy program's standard output (the input),
// as a format-2 and a format-3 reply of unit IMU-0001; a reply it accepts must export to the
// firmware's blocks. Refusal: std::runtime_error with the cause.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "calib/imu_calibration/external_reply.h"
#include "firmware_model/constants_exporter.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  for (int format : {2, 3}) {
    try {
      const adahrs::calib::CheckedReply reply =
          adahrs::calib::CheckExternalReply(bytes, "IMU-0001", format);
      (void)adahrs::firmware_model::ExportImuConstants(reply.constants);
    } catch (const std::runtime_error&) {
    }
  }
  return 0;
}
