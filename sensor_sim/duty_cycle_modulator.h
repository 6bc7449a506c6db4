// Edge timing of a free-running duty-cycle modulator (DCM) seen through a microcontroller's input
// capture, one report per firmware frame (physics.md §1.3, D): a rising edge every T2, the fall
// T1 = D·T2 later, every edge timestamped by a free-running 16-bit timer floored to its tick
// grid; once per frame the last period completed inside the frame is reported, T2 and T1 modulo
// 2^16. The DCM phase is continuous across frames, so the quantisation error moves from frame to
// frame and becomes a limit cycle when T2 is near a rational number of ticks (physics.md §6
// row 14). Period jitter T2·(1 + j·z), the unreported periods summed in one exact normal draw.
// Units: timer ticks (_cnt) relative to the start of the current frame.
// Capture formulas, jitter approximation, limit cycles: docs/models/adxl210e.md ("Edges and
// captures", "Limit cycles").
// Left out: the capture input's synchronisation delay (cancels in both differences), capture FIFO
// overflow and missed interrupts, timer-clock error (cancels in the ratio).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "sensor_sim/fast_math.h"

namespace adahrs::sensor_sim {

/// The period a frame reports, in ticks from the start of the frame, and where the frame start
/// lies on the timer's tick grid.
struct DcmPeriod {
  double start_cnt;       ///< rising edge r_j, ticks after the frame start (≥ 0)
  double length_cnt;      ///< r_{j+1} − r_j, ticks
  double grid_phase_cnt;  ///< fractional tick phase of the frame start, in [0, 1)
};

class DutyCycleModulator {
 public:
  /// `frame_cnt`: frame length in ticks. `initial_end_cnt` in (−T2, 0]: the last rising edge
  /// before the first frame. `initial_grid_phase_cnt` in [0, 1): tick phase of the first frame
  /// start.
  DutyCycleModulator(double frame_cnt, double initial_end_cnt, double initial_grid_phase_cnt);

  /// Advances one frame with the (mean) period `period_cnt` and returns the last complete period.
  /// `jitter_rms_cnt` is the rms error of one period (j·T2); `z_walk` and `z_period` are standard
  /// normal draws (ignored when the jitter is zero). Precondition: period_cnt ≤ frame_cnt / 2, so
  /// the reported period starts inside the frame. Inline: it runs once per chip and frame.
  DcmPeriod NextFrame(double period_cnt, double jitter_rms_cnt, double z_walk, double z_period) {
    // Rising edges follow last_end + k·T2. The last complete period ends at the last of them that
    // is ≤ frame end: it is edge number n = floor((frame − last_end)/T2), so the reported period
    // starts after m = n − 1 whole periods.
    const double m =
        static_cast<double>(FloorToInt64((frame_cnt_ - last_end_cnt_) / period_cnt) - 1);
    double start_cnt = last_end_cnt_ + m * period_cnt;
    double length_cnt = period_cnt;
    if (jitter_rms_cnt > 0.0) {
      start_cnt += SqrtOfCount(m) * jitter_rms_cnt * z_walk;
      length_cnt += jitter_rms_cnt * z_period;
    }
    if (start_cnt + length_cnt > frame_cnt_) start_cnt -= period_cnt;

    const DcmPeriod period{start_cnt, length_cnt, grid_phase_cnt_};
    last_end_cnt_ = start_cnt + length_cnt - frame_cnt_;
    const double next_phase_cnt = grid_phase_cnt_ + frame_cnt_;
    grid_phase_cnt_ = next_phase_cnt - static_cast<double>(FloorToInt64(next_phase_cnt));
    return period;
  }

 private:
  // √m for a whole number of periods m ≥ 0, bit-identical to std::sqrt(m): a table lookup for the
  // usual m (a frame holds frame/T2 ≈ 1…100 periods), which takes the square root's latency off
  // the frame's critical path.
  static double SqrtOfCount(double m) {
    static constexpr int kTableSize = 128;
    static const auto table = [] {
      std::array<double, kTableSize> t{};
      for (int k = 0; k < kTableSize; ++k) t[k] = std::sqrt(static_cast<double>(k));
      return t;
    }();
    return m < kTableSize ? table[static_cast<size_t>(m)] : std::sqrt(m);
  }

  double frame_cnt_;
  double last_end_cnt_;    // rising edge that ended the last reported period, from frame start
  double grid_phase_cnt_;  // tick phase of the current frame start
};

/// The timer difference a capture unit reports for edges at `from_cnt` and `to_cnt` (ticks after a
/// frame start whose tick phase is `grid_phase_cnt`), modulo 2^16. With `quantize`, each edge is
/// floored to the tick grid; without, the exact interval is rounded to the nearest tick (halves
/// away from zero). Arguments are tick counts well inside ±2^62 (a frame is ~3·10^5 ticks).
inline uint16_t CaptureIntervalCnt(double grid_phase_cnt,
                                   double from_cnt,
                                   double to_cnt,
                                   bool quantize) {
  const int64_t ticks =
      quantize ? FloorToInt64(grid_phase_cnt + to_cnt) - FloorToInt64(grid_phase_cnt + from_cnt)
               : RoundHalfAwayToInt64(to_cnt - from_cnt);
  return static_cast<uint16_t>(static_cast<uint64_t>(ticks) & 0xFFFFu);
}

}  // namespace adahrs::sensor_sim
