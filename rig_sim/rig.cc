#include "rig_sim/rig.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/random.h"
#include "rig_sim/ads_unit_device.h"
#include "rig_sim/imu_unit_device.h"

namespace adahrs::rig_sim {
namespace {

// A slot's unit: its model file's params when it names one, else the profile's draw.
template <typename Params>
Params SlotParams(const UnitSlotConfig& slot, const std::string& serial, const RigConfig& config) {
  if (!slot.model_params.is_null()) {
    return Params::FromJson(common::ParamReader(slot.model_params, slot.model_file, "$.params"));
  }
  Params p = Params::Draw(serial, slot.seed, config.model_profile);
  p.ApplyVariant(config.truth_variant);
  return p;
}

// Stream ids under each unit's seed (static_thermal_run.cc uses the same: 1 = noise).
constexpr uint64_t kNoiseStream = 1;
// Byte-fault streams are derived from the role's position so adding a fault never shifts another.
constexpr uint64_t kByteFaultSeedBase = 0xB17EFA17;

void WriteTruth(const std::filesystem::path& dir,
                const std::string& serial,
                const char* kind,
                uint64_t seed,
                sensor_sim::ModelProfile profile,
                const nlohmann::json& params) {
  std::filesystem::create_directories(dir);
  common::WriteFileAtomically(dir / (serial + ".json"),
                              nlohmann::json{{"serial", serial},
                                             {"kind", kind},
                                             {"seed", seed},
                                             {"model_profile", sensor_sim::ToString(profile)},
                                             {"params", params}}
                                      .dump(2) +
                                  "\n");
}

RigEnvironment InitialEnvironment(const RigConfig& config) {
  RigEnvironment env;
  env.imu_chamber_air_c = config.initial_air_c;
  env.ads_chamber_air_c = config.initial_air_c;
  env.local_gravity_mps2 = config.LocalGravityMps2();
  env.supply_v = config.station.supply_v;
  for (size_t i = 0; i < config.imus.size(); ++i) {
    env.imu_orientation[i] = config.imus[i].orientation;
  }
  return env;
}

}  // namespace

Rig::Rig(const RigConfig& config, const std::filesystem::path& run_dir)
    : config_(config),
      run_dir_(std::filesystem::absolute(run_dir)),
      host_(std::make_unique<DeviceHost>(config.time_scale, InitialEnvironment(config))) {
  std::filesystem::create_directories(run_dir_);
  uint64_t fault_stream = 0;
  const common::ParamReader root(config_.instruments, config_.source, "$.instruments");
  for (const InstrumentKind& kind : InstrumentKinds()) {
    if (!config.instruments.contains(kind.name)) continue;
    auto device = kind.make(root.Child(kind.name));
    instruments_.push_back({{"role", device->role()}, {"kind", kind.name}, {"doc", kind.doc_page}});
    if (const std::optional<int> address = device->GpibAddress())
      instruments_.back()["gpib_address"] = *address;
    AddDevice(std::move(device), kind.name, -1, fault_stream++);
  }
  for (size_t i = 0; i < config.imus.size(); ++i) {
    const UnitSlotConfig& slot = config.imus[i];
    ImuUnitDeviceConfig unit;
    unit.role = fmt::format("imu{}", i + 1);
    unit.slot = static_cast<int>(i);
    unit.serial_number = slot.serial_number;
    unit.params =
        SlotParams<sensor_sim::ImuUnitParams>(slot, ImuSerial(slot.serial_number), config);
    unit.noise_seed = common::Rng::Derive(slot.seed, kNoiseStream);
    unit.baud = slot.baud;
    unit.initial_air_c = config.initial_air_c;
    WriteTruth(run_dir_ / "truth",
               unit.params.serial,
               "imu",
               slot.seed,
               config.model_profile,
               unit.params.ToJson());
    units_.push_back({{"role", unit.role},
                      {"kind", "imu"},
                      {"slot", i + 1},
                      {"orientation", slot.orientation},
                      {"serial", unit.params.serial},
                      {"serial_number", slot.serial_number},
                      {"baud", slot.baud},
                      {"truth", "truth/" + unit.params.serial + ".json"}});
    auto device = std::make_unique<ImuUnitDevice>(unit);
    LogPackets(*device);
    AddDevice(std::move(device), "imu", unit.slot, fault_stream++);
  }
  for (size_t i = 0; i < config.ads.size(); ++i) {
    const UnitSlotConfig& slot = config.ads[i];
    AdsUnitDeviceConfig unit;
    unit.role = fmt::format("ads{}", i + 1);
    unit.serial_number = slot.serial_number;
    unit.params =
        SlotParams<sensor_sim::AdsUnitParams>(slot, AdsSerial(slot.serial_number), config);
    unit.noise_seed = common::Rng::Derive(slot.seed, kNoiseStream);
    unit.baud = slot.baud;
    unit.initial_air_c = config.initial_air_c;
    WriteTruth(run_dir_ / "truth",
               unit.params.serial,
               "ads",
               slot.seed,
               config.model_profile,
               unit.params.ToJson());
    units_.push_back({{"role", unit.role},
                      {"kind", "ads"},
                      {"slot", i + 1},
                      {"serial", unit.params.serial},
                      {"serial_number", slot.serial_number},
                      {"baud", slot.baud},
                      {"truth", "truth/" + unit.params.serial + ".json"}});
    auto device = std::make_unique<AdsUnitDevice>(unit);
    LogPackets(*device);
    AddDevice(std::move(device), "ads", -1, fault_stream++);
  }
  control_ = std::make_unique<RigControl>(targets_, config.time_scale);
  host_->SetLockstep(config.lockstep);
  host_->SetClockFile(run_dir_ / kClockFileName);
  ports_["control"] = host_->Add(std::make_unique<ControlPortDevice>(control_.get()));

  const nlohmann::json no_keys = nlohmann::json::object();
  const common::ParamReader faults_reader(no_keys, config_.source);
  for (const FaultSetting& fault : config.faults) {
    try {
      control_->SetFault(fault.role,
                         fault.fault,
                         fault.is_rate ? fmt::format("{}", fault.rate) : (fault.on ? "on" : "off"));
    } catch (const std::invalid_argument& e) {
      faults_reader.Fail(fault.where, e.what());
    }
  }
}

Rig::~Rig() { Stop(); }

void Rig::AddDevice(std::unique_ptr<SerialDevice> device,
                    const std::string& kind,
                    int imu_slot,
                    uint64_t fault_stream) {
  const std::string role = device->role();
  if (role == "control" || ports_.count(role)) {
    throw common::ParamError(config_.source + ": " + kind + " role '" + role + "' is used twice");
  }
  auto wrapped = std::make_unique<ByteFaultDevice>(
      std::move(device), common::Rng::Derive(kByteFaultSeedBase, fault_stream));
  targets_.push_back({role, wrapped.get(), imu_slot});
  ports_[role] = host_->Add(std::move(wrapped));
}

void Rig::WriteLinks() const {
  const std::filesystem::path dir = run_dir_ / "ports";
  std::filesystem::create_directories(dir);
  for (const auto& [role, path] : ports_) {
    // A new link under a temporary name, renamed over the old one: never a moment without it.
    const std::filesystem::path tmp = dir / (role + ".tmp");
    std::filesystem::remove(tmp);
    std::filesystem::create_symlink(path, tmp);
    std::filesystem::rename(tmp, dir / role);
  }
}

nlohmann::json Rig::Manifest() const {
  nlohmann::json links = nlohmann::json::object();
  for (const auto& [role, path] : ports_) links[role] = (run_dir_ / "ports" / role).string();
  return {
      {"format", "adahrs-rig-manifest"},
      {"version", kManifestVersion},
      {"pid", static_cast<int64_t>(::getpid())},
      {"time_scale", config_.time_scale},
      {"clock", {{"file", (run_dir_ / kClockFileName).string()}, {"lockstep", config_.lockstep}}},
      {"station",
       {{"name", config_.station.name},
        {"latitude_deg", config_.station.latitude_deg},
        {"height_m", config_.station.height_m},
        {"local_gravity_mps2", config_.LocalGravityMps2()}}},
      {"model_profile", sensor_sim::ToString(config_.model_profile)},
      {"truth_variant", sensor_sim::ToString(config_.truth_variant)},
      {"run_dir", run_dir_.string()},
      {"ports", ports_},
      {"links", links},
      {"units", units_},
      {"instruments", instruments_}};
}

void Rig::Start(const std::filesystem::path& manifest_path) {
  host_->Start();
  WriteLinks();
  if (manifest_path.has_parent_path())
    std::filesystem::create_directories(manifest_path.parent_path());
  common::WriteFileAtomically(manifest_path, Manifest().dump(2) + "\n");
  manifest_path_ = manifest_path;
}

void Rig::Stop() {
  host_->Stop();
  for (auto& log : packet_logs_) log->flush();
  RemoveManifestAndLinks();
}

void Rig::LogPackets(UnitDevice& device) {
  if (!config_.packet_log) return;
  const std::filesystem::path dir = run_dir_ / "packets";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / (device.role() + ".txt");
  auto log = std::make_unique<std::ofstream>(path);
  if (!*log) throw std::runtime_error(path.string() + ": cannot write the packet log");
  device.SetPacketLog(log.get());
  packet_logs_.push_back(std::move(log));
}

void Rig::RemoveManifestAndLinks() {
  if (manifest_path_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove(manifest_path_, ignored);
  for (const auto& [role, path] : ports_)
    std::filesystem::remove(run_dir_ / "ports" / role, ignored);
  std::filesystem::remove(run_dir_ / "ports", ignored);  // only when empty
  manifest_path_.clear();
}

std::string ClaimManifestPath(const std::filesystem::path& manifest_path) {
  std::error_code ec;
  if (!std::filesystem::exists(manifest_path, ec)) return "";
  nlohmann::json old;
  try {
    std::ifstream in(manifest_path);
    old = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    std::filesystem::remove(manifest_path, ec);
    return fmt::format("removed {}: not a readable manifest", manifest_path.string());
  }
  const int64_t pid = old.is_object() && old.contains("pid") && old["pid"].is_number_integer()
                          ? old["pid"].get<int64_t>()
                          : 0;
  if (pid > 0 && pid != ::getpid() && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM)) {
    throw std::runtime_error(
        fmt::format("{}: the rig of pid {} still runs with this manifest; stop it or give another "
                    "--manifest",
                    manifest_path.string(),
                    pid));
  }
  if (old.is_object() && old.contains("links") && old["links"].is_object()) {
    for (const auto& [role, link] : old["links"].items()) {
      if (link.is_string() && std::filesystem::is_symlink(link.get<std::string>(), ec)) {
        std::filesystem::remove(link.get<std::string>(), ec);
      }
    }
  }
  std::filesystem::remove(manifest_path, ec);
  return fmt::format(
      "removed {}, left by the rig of pid {}, which no longer runs", manifest_path.string(), pid);
}

std::string Rig::Control(const std::string& command) {
  std::string reply;
  host_->Run([&](std::vector<SerialDevice*>&, RigEnvironment& env) {
    reply = control_->Execute(command, host_->now_s(), env);
  });
  return reply;
}

}  // namespace adahrs::rig_sim
