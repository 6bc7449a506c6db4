// The Watlow 942 driver against the virtual 942 of the rig process (docs/rig/watlow-942.md).
#include "hil/drivers/watlow942_chamber.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "driver_test_util.h"

namespace adahrs::hil {
namespace {

using test::RigStation;
using ::testing::HasSubstr;

TEST(Watlow942Chamber, IdentifiesSetsAndReadsTheSetPoint) {
  RigStation s;
  Watlow942Chamber chamber(s.Entry("ads_chamber"), s.clock);
  EXPECT_EQ(chamber.Identify().detail, "MDL 942 1");  // rig config software_revision 1
  EXPECT_NEAR(chamber.ReadProcessC(), 25.0, 0.4);     // initial air, ±0.3 degC cycling
  chamber.SetSetPointC(-12.5);
  EXPECT_DOUBLE_EQ(chamber.ReadSetPointC(), -12.5);
  chamber.Hold();  // already holding (power-up mode): nothing to do, nothing refused
  EXPECT_DOUBLE_EQ(chamber.ReadSetPointC(), -12.5);
  // 4 degC down at the 3.5 degC/min cooling capacity, then the 120 s tail: minutes of simulation.
  chamber.SetSetPointC(21.0);
  EXPECT_TRUE(
      test::WaitUntil(s.clock, [&] { return std::abs(chamber.ReadProcessC() - 21.0) < 0.5; }));
}

TEST(Watlow942Chamber, LatchedErrorIsARefusalAndProfilesAreNotOffered) {
  RigStation s;
  Watlow942Chamber chamber(s.Entry("ads_chamber"), s.clock);
  try {
    chamber.SetSetPointC(150.0);  // range_high_c 100 in the rig config
    FAIL() << "the 942 accepted 150 degC";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.command(), "= SP1 150.0");
    EXPECT_EQ(e.reply(), "ER2 25");  // input out of limit (p. 18)
  }
  EXPECT_FALSE(chamber.SupportsProfiles());
  EXPECT_THROW(chamber.DownloadProfile("X", {F4End{}}), InstrumentError);
}

}  // namespace
}  // namespace adahrs::hil
