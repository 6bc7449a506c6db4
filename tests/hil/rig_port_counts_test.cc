// The lockstep rig's port counts file (hil/rig_port_counts.h): the packet index a reader derives
// from a packet's 8-bit counter and the rig's count, against hand-counted cases; the writer and a
// reader's counter through a real file: the slot found by its path, counts both ways, a reader's
// attachment taken up only when the rig acknowledges it, and released only by its own counter.
#include "hil/rig_port_counts.h"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

TEST(PacketIndexBelow, IsTheLargestIndexWithTheCounterValueBelowTheCount) {
  EXPECT_EQ(PacketIndexBelow(7, 8), 7u);            // the last packet counted
  EXPECT_EQ(PacketIndexBelow(7, 300), 263u);        // 263 = 256 + 7 <= 299
  EXPECT_EQ(PacketIndexBelow(44, 300), 44u);        // 300 is 300, 44 + 256 = 300 is not below it
  EXPECT_EQ(PacketIndexBelow(43, 300), 299u);       // 299 = 256 + 43
  EXPECT_EQ(PacketIndexBelow(255, 1000), 767u);     // 767 = 2 * 256 + 255 <= 999 < 1023
  EXPECT_EQ(PacketIndexBelow(7, 7), std::nullopt);  // not counted yet
  EXPECT_EQ(PacketIndexBelow(0, 0), std::nullopt);
}

class PortCountsFile : public ::testing::Test {
 protected:
  std::filesystem::path clock_ = std::filesystem::temp_directory_path() /
                                 ("port_counts_test_" + std::to_string(::getpid()) + ".clock");
  void TearDown() override { std::filesystem::remove(PortCountsPath(clock_)); }
};

TEST_F(PortCountsFile, AReaderFindsItsPortAndTheRigSeesItsCount) {
  RigPortCountsWriter rig(PortCountsPath(clock_), {"/dev/pts/7", "/dev/pts/12"});
  EXPECT_EQ(RigPortCounter::Open(clock_, "/dev/pts/1"), nullptr);                 // not listed
  EXPECT_EQ(RigPortCounter::Open(clock_.string() + "x", "/dev/pts/7"), nullptr);  // no file
  const std::unique_ptr<RigPortCounter> reader = RigPortCounter::Open(clock_, "/dev/pts/12");
  ASSERT_NE(reader, nullptr);
  rig.PublishProduced(0, 5);
  rig.PublishProduced(1, 900);
  EXPECT_EQ(reader->Produced(), 900u);
  EXPECT_EQ(rig.ReaderOf(1).token, 0u);  // not attached

  // The rig acknowledges from its own thread, as the host does at its next look.
  std::atomic<bool> done{false};
  uint64_t acknowledged = 0, start = 880;
  std::thread host([&] {
    while (!done) {
      const RigPortCountsWriter::Reader r = rig.ReaderOf(1);
      if (r.token != 0 && r.token != acknowledged) {
        acknowledged = r.token;
        rig.Acknowledge(1, r.token, ++start);  // each stream starts from the rig's count then
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  EXPECT_TRUE(reader->Attach(5.0));
  EXPECT_TRUE(reader->attached());
  EXPECT_EQ(reader->Consumed(), 881u);  // where the rig started the stream, not the reader
  EXPECT_EQ(rig.ReaderOf(1).consumed, 881u);
  reader->Consume(895);
  EXPECT_EQ(rig.ReaderOf(1).consumed, 895u);

  // A second counter of the port takes the slot; the first one closing does not release it.
  const std::unique_ptr<RigPortCounter> later = RigPortCounter::Open(clock_, "/dev/pts/12");
  ASSERT_NE(later, nullptr);
  EXPECT_TRUE(later->Attach(5.0));
  EXPECT_EQ(later->Consumed(), 882u);
  EXPECT_FALSE(reader->attached());
  reader->Detach();
  EXPECT_NE(rig.ReaderOf(1).token, 0u);
  later->Detach();
  EXPECT_EQ(rig.ReaderOf(1).token, 0u);
  done = true;
  host.join();
}

TEST_F(PortCountsFile, WithoutTheRigsAcknowledgementTheReaderIsNotAttached) {
  RigPortCountsWriter rig(PortCountsPath(clock_), {"/dev/pts/7"});
  const std::unique_ptr<RigPortCounter> reader = RigPortCounter::Open(clock_, "/dev/pts/7");
  ASSERT_NE(reader, nullptr);
  EXPECT_FALSE(reader->Attach(0.05));
  EXPECT_FALSE(reader->attached());
  EXPECT_EQ(rig.ReaderOf(0).token, 0u);
}

}  // namespace
}  // namespace adahrs::hil
