#include "proving/evaluation/simulated_raw_frame.h"

namespace adahrs::proving {

firmware_model::ImuRawFrame ToFirmwareRawFrame(const sensor_sim::ImuRawFrame& frame) {
  firmware_model::ImuRawFrame out{};
  for (int i = 0; i < 6; ++i) {
    out.t1_cnt[i] = frame.accel[i].t1_cnt;
    out.t2_cnt[i] = frame.accel[i].t2_cnt;
  }
  for (int g = 0; g < 3; ++g) {
    out.gyro_cnt[g] = frame.gyro_cnt[g];
    out.temp_cnt[g] = frame.temp_cnt[g];
  }
  return out;
}

}  // namespace adahrs::proving
