// The ATL rate-table driver against the virtual table of the rig process (docs/rig/rate-table.md).
#include "hil/drivers/atl_rate_table.h"
#include "adahrs_build_paths.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "driver_test_util.h"
#include "hil/drivers/atl_client_table.h"

namespace adahrs::hil {
namespace {

using test::RigStation;
using ::testing::HasSubstr;

TEST(AtlRateTable, ReachesTheCommandedRateReportsAtRateAndStops) {
  RigStation s;
  AtlRateTable table(s.Entry("rate_table"), s.clock);
  EXPECT_THAT(table.Identify().detail, HasSubstr("status word"));
  table.CommandRate(100.0, 100.0);
  // 0 → 100 deg/s at 100 deg/s^2 with a 50 ms rate loop is inside the 0.01 deg/s band after
  // 1.311 simulated s (docs/rig/rate-table.md); the wait allows for a loaded machine.
  ASSERT_TRUE(test::WaitUntil(s.clock, [&] { return table.AtRate(); }));
  // At rate: within the controller's 0.01 deg/s band, plus the 1e-5 once-per-revolution ripple.
  EXPECT_NEAR(table.ReadRateDps(), 100.0, 0.01 + 100.0 * 1e-5);
  // The world the units sense turns at the commanded rate too (the rig's own state, not the
  // driver).
  EXPECT_NEAR(test::EnvValue(s.rig, "table_rate_dps"), 100.0, 0.01 + 100.0 * 1e-5);
  table.Stop(200.0);
  ASSERT_TRUE(test::WaitUntil(s.clock, [&] { return std::abs(table.ReadRateDps()) < 0.01; }));
}

TEST(AtlRateTable, RefusalsNameTheCommandAndTheControllersReply) {
  RigStation s;
  AtlRateTable table(s.Entry("rate_table"), s.clock);
  // JOG takes whole deg/s: refused before anything is sent.
  try {
    table.CommandRate(10.5, 100.0);
    FAIL() << "a fractional JOG was sent";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.command(), "JOG 10.5");
    EXPECT_THAT(e.what(), HasSubstr("not sent"));
  }
  // 800 deg/s^2 is inside the ATL table's 1000 but beyond this table's 500 (rig config
  // max_accel_dps2): the controller refuses and its reply is quoted.
  try {
    table.CommandRate(50.0, 800.0);
    FAIL() << "the controller accepted an acceleration beyond its limit";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.command(), "ACL 800");
    EXPECT_THAT(e.reply(), HasSubstr("?OUT OF RANGE ACL"));
    EXPECT_THAT(e.what(), HasSubstr("rate_table on " + s.rig.Port("rate_table")));
  }
}

TEST(AtlRateTable, SilentTableIsNoReplyAfterTheBoundedRetries) {
  RigStation s;
  AtlRateTable table(s.Entry("rate_table"), s.clock);
  ASSERT_EQ(s.rig.Control("fault rate_table silent on"), "OK rate_table silent on");
  try {
    table.AtRate();
    FAIL() << "a silent table answered";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kNoReply);
    EXPECT_EQ(e.role(), "rate_table");
    EXPECT_EQ(e.command(), "STA?");
    // The station's retries: 2, so three attempts.
    EXPECT_THAT(e.what(), HasSubstr("3 attempts"));
  }
}

// A client that wrote here by mistake (a Prologix driver on the table's port) closes while the
// table is still refusing its lines: the next driver's first reply must be its own, not the tail
// of a refusal that was on the wire when it opened.
TEST(AtlRateTable, FirstReplyIsItsOwnWhileTheTableStillRefusesAStrangersLines) {
  RigStation s;
  for (int round = 0; round < 5; ++round) {
    {
      SerialPort stranger(s.Entry("rate_table").port, "stranger");
      std::string lines;
      // 200 refusals of 22 characters at 9600 baud: 4.6 simulated s, 23 ms of wall time.
      for (int i = 0; i < 200; ++i) lines += "++addr 5\n";
      stranger.Write(lines, std::chrono::seconds(5));
    }
    AtlRateTable table(s.Entry("rate_table"), s.clock);
    EXPECT_THAT(table.Identify().detail, HasSubstr("status word")) << "round " << round;
    EXPECT_NEAR(table.ReadRateDps(), 0.0, 0.01) << "round " << round;
  }
}

TEST(AtlRateTable, OpenInterlockIsAFault) {
  RigStation s;
  AtlRateTable table(s.Entry("rate_table"), s.clock);
  ASSERT_THAT(s.rig.Control("fault rate_table interlock_open on"), HasSubstr("OK"));
  try {
    table.AtRate();
    FAIL() << "AtRate ignored an open interlock";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kFault);
    EXPECT_THAT(e.what(), HasSubstr("interlock"));
  }
}

// The driver's commands must mean what the lab's table file says they mean.
TEST(AtlClientCommandTable, AgreesWithTheLabsTableFile) {
  const AtlCommandTable lab =
      AtlCommandTable::Load(std::string(ADAHRS_SOURCE_DIR) + "/rig_sim/data/atl_commands.json");
  const AtlCommandTable& client = AtlClientCommandTable();
  EXPECT_EQ(client.framing().line_end, lab.framing().line_end);
  EXPECT_EQ(client.framing().prompt, lab.framing().prompt);
  for (const AtlCommandSpec& spec : client.commands()) {
    SCOPED_TRACE(spec.mnemonic);
    const AtlCommandSpec* theirs = lab.Find(spec.mnemonic);
    ASSERT_NE(theirs, nullptr);
    EXPECT_EQ(spec.operation, theirs->operation);
    EXPECT_EQ(spec.confidence, theirs->confidence);
    if (spec.action) {
      ASSERT_TRUE(theirs->action.has_value());
      EXPECT_EQ(spec.action->argument, theirs->action->argument);
      EXPECT_EQ(spec.action->min, theirs->action->min);
      EXPECT_EQ(spec.action->max, theirs->action->max);
    }
    if (spec.query) {
      EXPECT_TRUE(theirs->query.has_value());
    }
  }
}

}  // namespace
}  // namespace adahrs::hil
