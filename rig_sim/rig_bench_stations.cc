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
                         {"retries", kInstrumentRetries}};
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
