#include "rig_sim/rig_bench_stations.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace adahrs::rig_sim {
namespace {

// Per-reply timeouts are clock time (the drivers divide them by the time scale). On a fast rig the
// station asks for kWallReplyTimeoutS of wall time per reply, so that a loaded 2-core host still
// answers in time, within the station format's limits (docs/station.md: 10...60,000 ms); never
// less than the drivers' own defaults at time scale 1.
constexpr double kWallReplyTimeoutS = 1.0;
constexpr int kMaxTimeoutMs = 60000;
constexpr int kInstrumentTimeoutMs = 1000;
constexpr int kInstrumentRetries = 2;
constexpr int kUnitTimeoutMs = 500;

int TimeoutMs(int minimum_ms, double time_scale) {
  return static_cast<int>(std::clamp(
      kWallReplyTimeoutS * 1000.0 * time_scale, double(minimum_ms), double(kMaxTimeoutMs)));
}
// The Prologix GPIB-USB adapter's virtual serial port; other instruments at their config's
// `baud`, 9600 when it has none (docs/rig/adts.md, docs/rig/).
constexpr unsigned kPrologixBaud = 115200;
constexpr unsigned kInstrumentBaud = 9600;
constexpr unsigned kControlBaud = 115200;

nlohmann::json Port(const std::string& path, unsigned baud, const char* flow) {
  return {{"path", path},
          {"baud", baud},
          {"data_bits", 8},
          {"parity", "N"},
          {"stop_bits", 1},
          {"flow", flow}};
}

bool OnBench(RigBench bench, const std::string& kind) {
  if (bench == RigBench::kImu) return kind == "aerosmith_atl" || kind == "watlow_f4";
  return kind == "watlow_942" || kind == "druck_adts_prologix";
}

// The virtual instrument's limits as the rig's config sets them, in the station's terms
// (docs/station.md "Limits"): the rate table's drive limits (docs/rig/rate-table.md), each
// chamber's set point range within what its air can reach, its heating and cooling capacity and
// as ramp limit the slower of the two (rig_sim/chamber_air.h; for the 942 also at most its
// controller's ramp limit, docs/rig/watlow-942.md), the ADTS's pressure ranges and rates
// (docs/rig/adts.md).
nlohmann::json Limits(const std::string& kind, const nlohmann::json& section) {
  const auto range_and_ramp = [](double low_c, double high_c, const nlohmann::json& air) {
    const double follow_c_per_min = std::min(air.at("heat_rate_c_per_min").get<double>(),
                                             air.at("cool_rate_c_per_min").get<double>());
    return nlohmann::json{{"min_c", std::max(low_c, air.at("min_c").get<double>())},
                          {"max_c", std::min(high_c, air.at("max_c").get<double>())},
                          {"max_ramp_c_per_min", follow_c_per_min},
                          {"heat_rate_c_per_min", air.at("heat_rate_c_per_min")},
                          {"cool_rate_c_per_min", air.at("cool_rate_c_per_min")}};
  };
  if (kind == "aerosmith_atl") {
    const nlohmann::json& physics = section.at("physics");
    return {{"max_rate_dps", physics.at("max_rate_dps")},
            {"max_accel_dps2", physics.at("max_accel_dps2")}};
  }
  if (kind == "watlow_f4") {
    const nlohmann::json& controller = section.at("controller");
    return range_and_ramp(controller.at("set_point_low_limit_c").get<double>(),
                          controller.at("set_point_high_limit_c").get<double>(),
                          section.at("chamber"));
  }
  if (kind == "watlow_942") {
    nlohmann::json limits = range_and_ramp(section.at("range_low_c").get<double>(),
                                           section.at("range_high_c").get<double>(),
                                           section.at("air"));
    limits["max_ramp_c_per_min"] = std::min(limits["max_ramp_c_per_min"].get<double>(),
                                            section.at("max_ramp_rate_c_per_min").get<double>());
    return limits;
  }
  const nlohmann::json& adts = section.at("adts");
  return {{"ps_min_pa", adts.at("ps_min_pa")},
          {"ps_max_pa", adts.at("ps_max_pa")},
          {"qc_max_pa", adts.at("qc_max_pa")},
          {"max_alt_rate_ft_per_min", adts.at("max_alt_rate_ft_per_min")},
          {"max_cas_rate_kt_per_min", adts.at("max_cas_rate_kt_per_min")}};
}

}  // namespace

hil::Station BenchStation(RigBench bench,
                          const nlohmann::json& manifest,
                          const RigConfig& config,
                          const std::string& source) {
  const nlohmann::json& links = manifest.at("links");
  const double time_scale = manifest.at("time_scale").get<double>();
  nlohmann::json instruments = nlohmann::json::object();
  for (const nlohmann::json& instrument : manifest.at("instruments")) {
    const std::string role = instrument.at("role");
    const std::string kind = instrument.at("kind");
    if (!OnBench(bench, kind)) continue;
    const nlohmann::json& section = config.instruments.at(kind);
    int address = 0;
    unsigned baud = section.value("baud", kInstrumentBaud);
    const char* flow = "none";
    if (kind == "watlow_f4") address = section.at("modbus_address").get<int>();
    if (kind == "druck_adts_prologix") {
      address = section.at("gpib_address").get<int>();
      baud = kPrologixBaud;
    }
    if (kind == "watlow_942") flow = "xonxoff";
    instruments[role] = {{"type", kind},
                         {"port", Port(links.at(role).get<std::string>(), baud, flow)},
                         {"address", address},
                         {"timeout_ms", TimeoutMs(kInstrumentTimeoutMs, time_scale)},
                         {"retries", kInstrumentRetries},
                         {"limits", Limits(kind, section)}};
  }
  const std::string unit_kind = bench == RigBench::kImu ? "imu" : "ads";
  nlohmann::json units = nlohmann::json::array();
  for (const nlohmann::json& unit : manifest.at("units")) {
    if (unit.at("kind") != unit_kind) continue;
    const std::string role = unit.at("role");
    units.push_back(
        {{"role", role},
         {"kind", unit_kind},
         {"slot", unit.at("slot")},
         {"timeout_ms", TimeoutMs(kUnitTimeoutMs, time_scale)},
         {"port",
          Port(links.at(role).get<std::string>(), unit.at("baud").get<unsigned>(), "none")}});
  }
  const nlohmann::json station = {
      {"name", config.station.name + (bench == RigBench::kImu ? " IMU bench" : " ADS bench")},
      {"time_scale", manifest.at("time_scale")},
      {"site",
       {{"latitude_deg", manifest.at("station").at("latitude_deg")},
        {"height_m", manifest.at("station").at("height_m")}}},
      {"instruments", instruments},
      {"units", units},
      {"operator",
       {{"type", "virtual_fixture"},
        {"port", Port(links.at("control").get<std::string>(), kControlBaud, "none")}}}};
  nlohmann::json with_clock = station;
  const nlohmann::json clock = manifest.value("clock", nlohmann::json::object());
  if (clock.value("lockstep", false)) with_clock["clock_file"] = clock.at("file");
  return hil::Station::FromJson(common::ParamReader(with_clock, source));
}

hil::Station WriteStationFile(const hil::Station& station, const std::filesystem::path& path) {
  {
    std::ofstream out(path);
    out << station.ToJson().dump(2) << "\n";
    if (!out) throw std::runtime_error(path.string() + ": cannot write the station file");
  }
  return hil::Station::Load(path.string());
}

}  // namespace adahrs::rig_sim
