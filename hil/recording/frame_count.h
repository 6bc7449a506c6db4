// Frames a unit ran between two of its recorded packets, from the 8-bit packet counter (wire
// format: docs/unit-protocol.md) and the arrival times: the counter's step modulo 256 (lost
// packets are frames too) plus the whole counter turns the arrival times say passed. Arrival
// times come in bursts (the host reads its ports in turn), so the counter, not the time, gives
// the step; the time only resolves the turns. 0 means the same packet logged twice.
// FrameCounter carries this past the counter: the frame index of each packet of one unit, so
// every recorded packet has a sample time on the unit's 100 Hz clock (recording format from
// version 3, columns frame and t_sample_s) and analyses never divide by the zero time step of a
// burst.
#pragma once

#include <cstdint>
#include <optional>

namespace adahrs::hil {

/// Modulus of the packet counter a unit sends.
inline constexpr int64_t kPacketCounterModulo = 256;

/// Frames between a packet with counter `previous_seq` and one with `seq` that arrived `dt_s`
/// later, the unit's frame period being `period_s` (> 0).
int64_t FramesBetween(uint32_t previous_seq, uint32_t seq, double dt_s, double period_s);

/// The unit's frame period: packets every 10 ms (docs/unit-protocol.md).
inline constexpr double kUnitFramePeriod_s = 0.01;

/// A unit's latest packet: its frame index, counter and arrival time.
struct FrameState {
  int64_t frame = 0;
  uint32_t seq = 0;
  double t_s = 0.0;
};

/// The frame index of each packet of one unit, in arrival order. The first packet's frame is the
/// one nearest its arrival time in frames (t_s / period) whose value modulo 256 is its counter,
/// so t_sample_s = frame * period stays near t_s; each later one adds FramesBetween. Seeded with
/// the unit's last recorded packet (a resumed run), the count continues from it: the frames the
/// unit ran while no process listened are then counted from the counter and the run's clock,
/// which a resume continues from the last recorded time, so whole counter turns of the downtime
/// are not counted.
class FrameCounter {
 public:
  FrameCounter() = default;
  explicit FrameCounter(FrameState last) : last_(last) {}
  /// The frame of a packet with counter `seq` (0…255 used) that arrived at `t_s`. With the
  /// packet's `index` on a lockstep rig's count (hil/rig_port_counts.h) and the previous
  /// packet's, the step is the difference of the indices, exactly; otherwise FramesBetween.
  int64_t Next(uint32_t seq, double t_s, std::optional<int64_t> index = std::nullopt);
  const std::optional<FrameState>& last() const { return last_; }

 private:
  std::optional<FrameState> last_;
  std::optional<int64_t> last_index_;  // the last packet's index on a lockstep rig's count
};

/// The sample time of frame `frame` on the unit's clock, seconds.
inline double SampleTimeS(int64_t frame) { return static_cast<double>(frame) * kUnitFramePeriod_s; }

}  // namespace adahrs::hil
