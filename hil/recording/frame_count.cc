#include "hil/recording/frame_count.h"

#include <algorithm>
#include <cmath>

namespace adahrs::hil {

int64_t FramesBetween(uint32_t previous_seq, uint32_t seq, double dt_s, double period_s) {
  const int64_t step =
      (static_cast<int64_t>(seq) - static_cast<int64_t>(previous_seq)) & (kPacketCounterModulo - 1);
  const double extra =
      (dt_s / period_s - static_cast<double>(step)) / static_cast<double>(kPacketCounterModulo);
  return step + kPacketCounterModulo * std::max<int64_t>(0, std::llround(extra));
}

int64_t FrameCounter::Next(uint32_t seq, double t_s, std::optional<int64_t> index) {
  int64_t frame = 0;
  if (last_ && index && last_index_ && *index >= *last_index_) {
    // Both on the rig's count of this unit's packets (a count that went back is a new rig).
    frame = last_->frame + (*index - *last_index_);
  } else if (last_) {
    frame = last_->frame + FramesBetween(last_->seq, seq, t_s - last_->t_s, kUnitFramePeriod_s);
  } else {
    // The frame nearest t_s / period with frame mod 256 = seq mod 256, never negative.
    const int64_t near = std::llround(std::max(0.0, t_s) / kUnitFramePeriod_s);
    const int64_t residue = static_cast<int64_t>(seq) & (kPacketCounterModulo - 1);
    frame = near - ((near - residue) & (kPacketCounterModulo - 1));
    if (near - frame > kPacketCounterModulo / 2) frame += kPacketCounterModulo;
    if (frame < 0) frame += kPacketCounterModulo;
  }
  last_ = FrameState{frame, seq, t_s};
  last_index_ = index;
  return frame;
}

}  // namespace adahrs::hil
