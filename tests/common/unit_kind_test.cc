// UnitKind: its codes against the flash image layout of docs/firmware-compensator.md ("word 1 unit
// kind (1 IMU, 2 ADS)"), its names against the file formats (docs/sequences.md, docs/studies.md:
// `unit_kind` is "imu" or "ads").
#include "common/unit_kind.h"

#include <gtest/gtest.h>

namespace adahrs::common {
namespace {

TEST(UnitKind, CodesAreTheFirmwareOnes) {
  EXPECT_EQ(static_cast<int>(UnitKind::kImu), 1);
  EXPECT_EQ(static_cast<int>(UnitKind::kAds), 2);
}

TEST(UnitKind, NamesAreTheFileFormatsOnes) {
  EXPECT_STREQ(UnitKindName(UnitKind::kImu), "imu");
  EXPECT_STREQ(UnitKindName(UnitKind::kAds), "ads");
  EXPECT_EQ(ParseUnitKind("imu"), UnitKind::kImu);
  EXPECT_EQ(ParseUnitKind("ads"), UnitKind::kAds);
}

TEST(UnitKind, ParseTakesTheExactNameOnly) {
  for (const char* text : {"", "IMU", "Ads", " imu", "imu ", "im", "adss", "1"}) {
    EXPECT_EQ(ParseUnitKind(text), std::nullopt) << '"' << text << '"';
  }
}

}  // namespace
}  // namespace adahrs::common
