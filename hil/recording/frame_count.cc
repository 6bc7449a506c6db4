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

}  // namespace adahrs::hil
