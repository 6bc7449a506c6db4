#include "sensor_sim/duty_cycle_modulator.h"

#include <cmath>

namespace adahrs::sensor_sim {

DutyCycleModulator::DutyCycleModulator(double frame_cnt, double initial_end_cnt,
                                       double initial_grid_phase_cnt)
    : frame_cnt_(frame_cnt),
      last_end_cnt_(initial_end_cnt),
      grid_phase_cnt_(initial_grid_phase_cnt) {}

DcmPeriod DutyCycleModulator::NextFrame(double period_cnt, double jitter_rms_cnt, double z_walk,
                                        double z_period) {
  // Rising edges follow last_end + k·T2. The last complete period ends at the last of them that is
  // ≤ frame end: it is edge number n = floor((frame − last_end)/T2), so the reported period starts
  // after m = n − 1 whole periods.
  const double m = std::floor((frame_cnt_ - last_end_cnt_) / period_cnt) - 1.0;
  double start_cnt = last_end_cnt_ + m * period_cnt;
  double length_cnt = period_cnt;
  if (jitter_rms_cnt > 0.0) {
    start_cnt += std::sqrt(m) * jitter_rms_cnt * z_walk;
    length_cnt += jitter_rms_cnt * z_period;
  }
  if (start_cnt + length_cnt > frame_cnt_) start_cnt -= period_cnt;

  const DcmPeriod period{start_cnt, length_cnt, grid_phase_cnt_};
  last_end_cnt_ = start_cnt + length_cnt - frame_cnt_;
  const double next_phase_cnt = grid_phase_cnt_ + frame_cnt_;
  grid_phase_cnt_ = next_phase_cnt - std::floor(next_phase_cnt);
  return period;
}

uint16_t CaptureIntervalCnt(double grid_phase_cnt, double from_cnt, double to_cnt, bool quantize) {
  const int64_t ticks =
      quantize ? static_cast<int64_t>(std::floor(grid_phase_cnt + to_cnt)) -
                     static_cast<int64_t>(std::floor(grid_phase_cnt + from_cnt))
               : static_cast<int64_t>(std::llround(to_cnt - from_cnt));
  return static_cast<uint16_t>(static_cast<uint64_t>(ticks) & 0xFFFFu);
}

}  // namespace adahrs::sensor_sim
