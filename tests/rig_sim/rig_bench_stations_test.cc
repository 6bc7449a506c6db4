// The stations the rig writes for its benches (rig_sim/rig_bench_stations.h) declare the virtual
// instruments' limits as the rig's config sets them: the built-in config's values as
// docs/rig/*.md state them, and a changed config changes the station.
#include "rig_sim/rig_bench_stations.h"

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

// A manifest as a running rig writes it, for the roles the benches use (paths need not exist:
// the station reader compares absent paths by name).
nlohmann::json Manifest() {
  nlohmann::json links = nlohmann::json::object();
  for (const char* role :
       {"rate_table", "imu_chamber", "ads_chamber", "adts", "imu1", "ads1", "control"}) {
    links[role] = std::string("/nonexistent/ports/") + role;
  }
  return {{"links", links},
          {"time_scale", 10.0},
          {"station", {{"latitude_deg", 34.7}, {"height_m", 190.0}}},
          {"instruments",
           {{{"role", "rate_table"}, {"kind", "aerosmith_atl"}},
            {{"role", "imu_chamber"}, {"kind", "watlow_f4"}},
            {{"role", "ads_chamber"}, {"kind", "watlow_942"}},
            {{"role", "adts"}, {"kind", "druck_adts_prologix"}}}},
          {"units",
           {{{"role", "imu1"}, {"kind", "imu"}, {"slot", 1}, {"baud", 115200}},
            {{"role", "ads1"}, {"kind", "ads"}, {"slot", 1}, {"baud", 115200}}}}};
}

hil::InstrumentLimits LimitsOf(RigBench bench, const nlohmann::json& config, const char* role) {
  const hil::Station station =
      BenchStation(bench, Manifest(), RigConfig::FromJson(config, "config"), "station");
  const hil::InstrumentEntry* entry = station.Instrument(role);
  if (entry == nullptr) throw std::runtime_error(std::string("no ") + role);
  return entry->limits;
}

TEST(RigBenchStations, DeclareTheBuiltInInstrumentsLimits) {
  const nlohmann::json config = DefaultRigConfig();
  // docs/rig/rate-table.md: JOG −360…360 °/s, ACL drive limit 500 °/s².
  const hil::InstrumentLimits table = LimitsOf(RigBench::kImu, config, "rate_table");
  EXPECT_EQ(table.max_rate_dps, 360.0);
  EXPECT_EQ(table.max_accel_dps2, 500.0);
  // docs/rig/watlow-f4.md: set point limits −70…180 °C; air heats at 5, cools at 3.5 °C/min.
  const hil::InstrumentLimits f4 = LimitsOf(RigBench::kImu, config, "imu_chamber");
  EXPECT_EQ(f4.min_c, -70.0);
  EXPECT_EQ(f4.max_c, 180.0);
  EXPECT_EQ(f4.max_ramp_c_per_min, 3.5);
  EXPECT_EQ(f4.heat_rate_c_per_min, 5.0);
  EXPECT_EQ(f4.cool_rate_c_per_min, 3.5);
  // docs/rig/watlow-942.md: rL/rH −50…100 °C, the same air.
  const hil::InstrumentLimits w942 = LimitsOf(RigBench::kAds, config, "ads_chamber");
  EXPECT_EQ(w942.min_c, -50.0);
  EXPECT_EQ(w942.max_c, 100.0);
  EXPECT_EQ(w942.max_ramp_c_per_min, 3.5);
  EXPECT_EQ(w942.heat_rate_c_per_min, 5.0);
  EXPECT_EQ(w942.cool_rate_c_per_min, 3.5);
  // docs/rig/adts.md and protocols.md §4.7: Ps 7,500…135,500 Pa, Qc ≤ 90,000 Pa,
  // 100,000 ft/min, 2,000 kt/min.
  const hil::InstrumentLimits adts = LimitsOf(RigBench::kAds, config, "adts");
  EXPECT_EQ(adts.ps_min_pa, 7500.0);
  EXPECT_EQ(adts.ps_max_pa, 135500.0);
  EXPECT_EQ(adts.qc_max_pa, 90000.0);
  EXPECT_EQ(adts.max_alt_rate_ft_per_min, 100000.0);
  EXPECT_EQ(adts.max_cas_rate_kt_per_min, 2000.0);
}

TEST(RigBenchStations, FollowTheRigsConfig) {
  nlohmann::json config = DefaultRigConfig();
  config["instruments"]["watlow_942"]["range_high_c"] = 60.0;
  config["instruments"]["watlow_942"]["max_ramp_rate_c_per_min"] = 2.0;  // below the air's 3.5
  config["instruments"]["watlow_f4"]["chamber"]["heat_rate_c_per_min"] = 2.5;  // below cooling
  config["instruments"]["watlow_f4"]["chamber"]["min_c"] = -40.0;  // air warmer than SP limit
  config["instruments"]["aerosmith_atl"]["physics"]["max_rate_dps"] = 200.0;
  const hil::InstrumentLimits w942 = LimitsOf(RigBench::kAds, config, "ads_chamber");
  EXPECT_EQ(w942.max_c, 60.0);
  EXPECT_EQ(w942.max_ramp_c_per_min, 2.0);
  const hil::InstrumentLimits f4 = LimitsOf(RigBench::kImu, config, "imu_chamber");
  EXPECT_EQ(f4.min_c, -40.0);
  EXPECT_EQ(f4.max_ramp_c_per_min, 2.5);
  EXPECT_EQ(f4.heat_rate_c_per_min, 2.5);
  EXPECT_EQ(LimitsOf(RigBench::kImu, config, "rate_table").max_rate_dps, 200.0);
}

}  // namespace
}  // namespace adahrs::rig_sim
