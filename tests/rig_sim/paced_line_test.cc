#include "rig_sim/paced_line.h"

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

TEST(PacedLine, ReleasesEachByteWhenItsStopBitHasLeft) {
  PacedLine line(115200, 512);
  const std::vector<uint8_t> frame(89, 0x55);
  ASSERT_TRUE(line.Queue(frame, 1.0));
  // 8N1: 10 bits per byte, 115,200 bit/s → 86.8 µs per byte; 89 bytes end at 7.726 ms.
  const double byte_s = 10.0 / 115200.0;
  std::vector<uint8_t> out;
  line.Release(1.0 + 10 * byte_s - 1e-7, out);
  EXPECT_EQ(out.size(), 9u);
  line.Release(1.0 + 10 * byte_s, out);
  EXPECT_EQ(out.size(), 10u);
  line.Release(1.0 + 89 * byte_s, out);
  EXPECT_EQ(out.size(), 89u);
}

TEST(PacedLine, AFrameQueuedWhileTheLineIsBusyFollowsTheLastByte) {
  PacedLine line(9600, 512);
  const double byte_s = 10.0 / 9600.0;
  ASSERT_TRUE(line.Queue(std::vector<uint8_t>(10, 1), 0.0));
  ASSERT_TRUE(line.Queue(std::vector<uint8_t>(5, 2), 2 * byte_s));
  std::vector<uint8_t> out;
  line.Release(14 * byte_s + 1e-7, out);
  EXPECT_EQ(out.size(), 14u);
  line.Release(15 * byte_s, out);
  EXPECT_EQ(out.size(), 15u);
}

TEST(PacedLine, RefusesAFrameThatDoesNotFitTheTransmitBuffer) {
  // 57,600 baud: an 89-byte packet takes 15.45 ms; at 100 Hz the buffer fills and whole packets
  // are refused (docs/unit-protocol.md §1: too slow for compensated IMU output).
  PacedLine line(57600, 256);
  const std::vector<uint8_t> packet(89, 0);
  int refused = 0;
  for (int k = 0; k < 100; ++k) refused += line.Queue(packet, 0.01 * k) ? 0 : 1;
  // Capacity 256 bytes = 2 packets waiting + the one on the wire; the line drains 0.647 packet
  // per 10 ms, so ~35 % of 100 packets are refused once it is full.
  EXPECT_GT(refused, 25);
  EXPECT_LT(refused, 40);
}

TEST(PacedLine, FlushLosesWhatIsUnsentButKeepsWhatHasLeft) {
  PacedLine line(115200, 512);
  const double byte_s = 10.0 / 115200.0;
  ASSERT_TRUE(line.Queue(std::vector<uint8_t>(50, 7), 0.0));
  line.Flush(20.5 * byte_s);
  std::vector<uint8_t> out;
  line.Release(1.0, out);
  EXPECT_EQ(out.size(), 20u);
  // After the flush the line is free at once.
  ASSERT_TRUE(line.Queue(std::vector<uint8_t>(1, 9), 1.0));
  line.Release(1.0 + byte_s, out);
  EXPECT_EQ(out.size(), 21u);
}

TEST(PacedLine, RefusesAnImpossibleLineRate) {
  EXPECT_THROW(PacedLine(0, 512), std::invalid_argument);
  EXPECT_THROW(PacedLine(115200, 0), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::rig_sim
