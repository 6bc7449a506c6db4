// Frames a unit ran between two of its recorded packets, from the 8-bit packet counter (wire
// format: docs/unit-protocol.md) and the arrival times: the counter's step modulo 256 (lost
// packets are frames too) plus the whole counter turns the arrival times say passed. Arrival
// times come in bursts (the host reads its ports in turn), so the counter, not the time, gives
// the step; the time only resolves the turns. 0 means the same packet logged twice.
#pragma once

#include <cstdint>

namespace adahrs::hil {

/// Modulus of the packet counter a unit sends.
inline constexpr int64_t kPacketCounterModulo = 256;

/// Frames between a packet with counter `previous_seq` and one with `seq` that arrived `dt_s`
/// later, the unit's frame period being `period_s` (> 0).
int64_t FramesBetween(uint32_t previous_seq, uint32_t seq, double dt_s, double period_s);

}  // namespace adahrs::hil
