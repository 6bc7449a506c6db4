// adahrs download's library against the virtual rig as a separate process: constants written,
// read back, committed and the unit streaming in its calibrated mode with values equal to the
// double reference compensator on the same raw frames within the exporter's stated error bound;
// a corrupted line refuses the download and commits nothing.
#include "calib/download/constants_download.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/download/readback_check.h"
#include "firmware_model/reference_compensator.h"
#include "hil/drivers/unit_serial.h"
#include "tests/firmware_model/realistic_constants.h"
#include "tests/support/rig_process.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;
using ::testing::HasSubstr;

// Rig time scale: 5 simulated s per wall s keeps the test short; UnitLink's reply floor is wall
// time.
constexpr double kTimeScale = 5.0;

ConstantsFile ImuFileFor(const std::string& serial, uint64_t seed) {
  ConstantsFile file;
  file.serial = serial;
  file.kind = hil::UnitKind::kImu;
  file.strategy = "reference";
  file.created_utc = "2024-05-01T09:00:00Z";
  file.software_version = "0.1.0";
  file.imu = fm::testing::RealisticImu(seed);
  return file;
}

hil::UnitEntry Unit(const hil::Station& station, const std::string& role) {
  for (const hil::UnitEntry& unit : station.units) {
    if (unit.role == role) return unit;
  }
  throw std::runtime_error("no unit " + role);
}

TEST(ReadbackCheckTest, FindsTheFirstDifferingWordOrLength) {
  const std::vector<int16_t> written = {1, -2, 0x1234, 7};
  EXPECT_FALSE(CompareReadback(written, written));
  const std::vector<int16_t> flipped = {1, -2, 0x1236, 7};  // one bit of word 2
  const auto mismatch = CompareReadback(written, flipped);
  ASSERT_TRUE(mismatch);
  EXPECT_EQ(mismatch->word_index, 2u);
  EXPECT_EQ(mismatch->Describe(), "word 2: wrote 0x1234, read 0x1236");
  const std::vector<int16_t> shorter = {1, -2, 0x1234};
  EXPECT_EQ(CompareReadback(written, shorter)->Describe(), "wrote 4 words, read 3");
}

TEST(ConstantsBlocksTest, ImuSetIsTwentySevenBlocksOfTheTargetLengths) {
  const ConstantsBlocks blocks = ExportConstantsBlocks(ImuFileFor("IMU-0001", 3), "c.json");
  ASSERT_EQ(blocks.blocks.size(), 27u);
  for (const ConstantsBlock& block : blocks.blocks) {
    // Lengths from docs/unit-protocol.md §6.2: thermal 17, accel 30, gyro 16, matrices 27 words;
    // format 3: switch 10, scale factors 13, accelerometer nonlinearity 9, g-sensitivity 27.
    const uint8_t id = block.block_id;
    const size_t expected = id <= 0x09   ? 17
                            : id == 0x0A ? 30
                            : id <= 0x0D ? 16
                            : id <= 0x0F ? 27
                            : id == 0x10 ? 10
                            : id <= 0x19 ? 13
                            : id == 0x1A ? 9
                                         : 27;
    EXPECT_EQ(block.words.size(), expected) << block.name;
    EXPECT_EQ(id, blocks.blocks.front().block_id + (&block - blocks.blocks.data()));
  }
  // Format-2 constants: the switch block is written, with the stages off.
  EXPECT_EQ(blocks.blocks[15].name, "scale-temperature switch");
  EXPECT_EQ(blocks.blocks[15].words[0], 0);
  ConstantsFile empty = ImuFileFor("IMU-0001", 3);
  empty.imu.reset();
  EXPECT_THAT([&] { ExportConstantsBlocks(empty, "c.json"); },
              ::testing::ThrowsMessage<ConstantsBlocksError>(HasSubstr("c.json (IMU-0001)")));
}

class ConstantsDownloadRigTest : public ::testing::Test {
 protected:
  ConstantsDownloadRigTest()
      : rig_(kTimeScale),
        station_(hil::Station::Load(rig_.WriteStation())),
        clock_(hil::MakeClock(station_.time_scale)) {}
  adahrs::testing::RigProcess rig_;
  hil::Station station_;
  std::unique_ptr<hil::Clock> clock_;
};

TEST_F(ConstantsDownloadRigTest, CommittedConstantsCompensateLikeTheReferenceWithinTheExportBound) {
  hil::UnitLink link(Unit(station_, "imu1"), *clock_);
  const hil::IdentifyInfo before = link.Identify();
  const std::string serial = hil::UnitSerialText(hil::UnitKind::kImu, before.serial_number);
  const ConstantsFile file = ImuFileFor(serial, 11);
  const DownloadResult result = DownloadConstants(link, file, "imu1.json");

  EXPECT_EQ(result.after.constants_version, before.constants_version + 1);
  EXPECT_TRUE(result.after.constants_valid);
  EXPECT_EQ(result.after.constants_crc, result.commit.constants_crc);
  const hil::IdentifyInfo now = link.Identify();
  EXPECT_EQ(now.mode, static_cast<uint8_t>(fm::ImuCompensationMode::kFullyCalibrated));

  link.Poll(std::chrono::milliseconds(200));  // drop packets sent before the mode change
  int compared = 0;
  double worst_mps2 = 0.0, worst_dps = 0.0;
  const fm::ImuExportReport& bound = result.blocks.imu_report;
  while (compared < 50) {
    for (const hil::ReceivedPacket& packet : link.Poll(std::chrono::milliseconds(500))) {
      const auto& data = std::get<fm::ImuDataPayload>(packet.data);
      ASSERT_EQ(data.mode, fm::ImuCompensationMode::kFullyCalibrated);
      ASSERT_EQ(data.compensated.flags, 0) << "saturated: the comparison would be meaningless";
      const auto fixed = fm::ImuFrameToDouble(data.mode, data.compensated);
      const auto reference = fm::ImuReference(*file.imu, data.mode, data.raw);
      for (int i = 0; i < 3; ++i) {
        worst_mps2 = std::max(worst_mps2, std::abs(fixed[i] - reference[i]));
        worst_dps = std::max(worst_dps, std::abs(fixed[3 + i] - reference[3 + i]));
        // Pair disagreement (g): its error is bounded by the sensor-calibrated accel bound.
        EXPECT_LE(std::abs(fixed[6 + i] - reference[6 + i]), bound.accel_g);
      }
      ++compared;
    }
  }
  std::printf(
      "compared %d packets: worst |A - A_ref| %.3g m/s^2 (bound %.3g), "
      "worst |G - G_ref| %.3g deg/s (bound %.3g)\n",
      compared,
      worst_mps2,
      bound.accel_mps2,
      worst_dps,
      bound.rate_full_dps);
  EXPECT_LE(worst_mps2, bound.accel_mps2);
  EXPECT_LE(worst_dps, bound.rate_full_dps);
}

TEST_F(ConstantsDownloadRigTest, ConstantsOfAnotherUnitAreRefusedBeforeAnythingIsWritten) {
  hil::UnitLink link(Unit(station_, "imu2"), *clock_);
  const hil::IdentifyInfo before = link.Identify();
  try {
    DownloadConstants(link, ImuFileFor("IMU-9999", 2), "other.json");
    FAIL() << "accepted";
  } catch (const DownloadError& e) {
    EXPECT_THAT(e.what(), HasSubstr("other.json into imu2"));
    EXPECT_THAT(e.what(), HasSubstr("the constants are for IMU-9999"));
    EXPECT_THAT(e.what(), HasSubstr("nothing committed"));
  }
  EXPECT_EQ(link.Identify().constants_version, before.constants_version);
}

TEST_F(ConstantsDownloadRigTest, CorruptedLineRefusesTheDownloadAndCommitsNothing) {
  const auto refused = [](const fm::DecoderCounters& c) {
    return uint64_t{c.bad_crc} + c.bad_length + c.unknown_type + c.resync_bytes_skipped;
  };
  hil::IdentifyInfo before;
  uint64_t by_link = 0;
  {
    hil::UnitLink link(Unit(station_, "imu3"), *clock_);
    before = link.Identify();
    const std::string serial = hil::UnitSerialText(hil::UnitKind::kImu, before.serial_number);
    // 2 % of bytes get a bit flipped: a 50-byte exchange survives with p = 0.98^50 = 0.36, three
    // attempts with 0.74, the ~32 exchanges of a download all with 0.74^32 < 1e-4.
    ASSERT_EQ(rig_.Control("fault imu3 corrupt_rate 0.02"), "OK imu3 corrupt_rate 0.02");
    try {
      DownloadConstants(link, ImuFileFor(serial, 5), "imu3.json");
      FAIL() << "a download over a corrupting line was accepted";
    } catch (const DownloadError& e) {
      std::printf("refused: %s\n", e.what());
      EXPECT_THAT(e.what(), HasSubstr("imu3.json into imu3"));
      EXPECT_THAT(e.what(), HasSubstr("nothing committed"));
      EXPECT_FALSE(e.verified());
    }
    ASSERT_EQ(rig_.Control("fault imu3 corrupt_rate 0"), "OK imu3 corrupt_rate 0");
    by_link = refused(link.decoder_counters());
  }  // the port is one client's at a time
  hil::UnitLink fresh(Unit(station_, "imu3"), *clock_);
  const hil::IdentifyInfo after = fresh.Identify();
  EXPECT_EQ(after.constants_version, before.constants_version);
  EXPECT_EQ(after.constants_crc, before.constants_crc);
  EXPECT_FALSE(after.constants_valid);
  // The flipped bits were seen and refused by a decoder: the unit's when a request was hit, the
  // link's when a reply was (which side is a matter of chance: a refusal at IDENTIFY may have
  // sent no corrupted request at all).
  const uint64_t by_unit = refused(fresh.ReadCounters().decoder);
  std::printf("refusals: unit decoder %llu, link decoder %llu\n",
              static_cast<unsigned long long>(by_unit),
              static_cast<unsigned long long>(by_link));
  EXPECT_GT(by_unit + by_link, 0u);
}

}  // namespace
}  // namespace adahrs::calib
