// CheckPorts (`adahrs ports check`) against the virtual rig as a separate process: a station with
// two instruments' ports swapped fails those rows, and the next check with the right ports passes
// every row on its first try (nothing the wrong client sent or was sent is left on the lines).
#include "hil/drivers/port_check.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../support/rig_process.h"
#include "hil/clock.h"
#include "hil/station.h"

namespace adahrs::hil {
namespace {

constexpr double kTimeScale = 200.0;

std::string FailedRows(const std::vector<PortCheckRow>& rows) {
  std::string failed;
  for (const PortCheckRow& row : rows) {
    if (!row.ok) failed += row.role + ": " + row.status + "\n";
  }
  return failed;
}

void SwapPorts(nlohmann::json& station, const std::string& a, const std::string& b) {
  std::swap(station["instruments"][a]["port"]["path"], station["instruments"][b]["port"]["path"]);
}

class PortCheckAfterSwap : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(PortCheckAfterSwap, NextCorrectCheckPassesFirstTime) {
  const auto& [a, b] = GetParam();
  testing::RigProcess rig(kTimeScale);
  ScaledClock clock(kTimeScale);
  const Station swapped = Station::Load(
      rig.WriteStation("swapped.json", [&](nlohmann::json& station) { SwapPorts(station, a, b); }));
  const std::vector<PortCheckRow> swapped_rows = CheckPorts(swapped, clock);
  EXPECT_NE(FailedRows(swapped_rows), "") << "a check with " << a << " and " << b << " swapped";

  const Station correct = Station::Load(rig.WriteStation());
  EXPECT_EQ(FailedRows(CheckPorts(correct, clock)), "");
}

INSTANTIATE_TEST_SUITE_P(
    Instruments,
    PortCheckAfterSwap,
    ::testing::Values(std::pair<std::string, std::string>{"rate_table", "imu_chamber"},
                      std::pair<std::string, std::string>{"rate_table", "ads_chamber"},
                      std::pair<std::string, std::string>{"rate_table", "adts"}),
    [](const auto& info) { return info.param.first + "_" + info.param.second; });

}  // namespace
}  // namespace adahrs::hil
