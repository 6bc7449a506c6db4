#include "hil/drivers/unit_mode.h"

#include <memory>
#include <variant>

#include <fmt/format.h>

#include "hil/drivers/unit_link.h"

namespace adahrs::hil {
namespace {

namespace fm = firmware_model;
using Kind = InstrumentError::Kind;

constexpr char kRole[] = "unit";

struct OpenUnit {
  std::unique_ptr<UnitLink> link;
  IdentifyInfo identity{};
};

std::unique_ptr<UnitLink> Open(const UnitPort& port, UnitKind kind, const Clock& clock) {
  UnitEntry entry;
  entry.role = kRole;
  entry.kind = kind;
  entry.port = port.port;
  entry.timeout_ms = port.timeout_ms;
  return std::make_unique<UnitLink>(entry, clock);
}

// The link opened for the unit's own kind: an IMU is assumed first; a unit that answers or
// streams as the other kind is opened again as an ADS.
OpenUnit Identify(const UnitPort& port, const Clock& clock) {
  OpenUnit unit{Open(port, UnitKind::kImu, clock), {}};
  try {
    unit.identity = unit.link->Identify();
    return unit;
  } catch (const InstrumentError& e) {
    if (e.kind() != Kind::kWrongIdentity) throw;
  }
  unit.link.reset();  // the port is taken exclusively: closed before the second open
  unit.link = Open(port, UnitKind::kAds, clock);
  unit.identity = unit.link->Identify();
  return unit;
}

int PacketMode(const ReceivedPacket& packet) {
  if (const auto* imu = std::get_if<fm::ImuDataPayload>(&packet.data)) {
    return static_cast<int>(imu->mode);
  }
  return static_cast<int>(std::get<fm::AdsDataPayload>(packet.data).mode);
}

[[noreturn]] void Fail(const UnitPort& port,
                       Kind kind,
                       const std::string& command,
                       const std::string& detail) {
  throw InstrumentError(kind, kRole, port.port.path, command, "", detail);
}

}  // namespace

std::string UnitModeName(UnitKind kind, uint8_t mode) {
  if (kind == UnitKind::kImu) {
    switch (mode) {
      case 0:
        return "raw";
      case 1:
        return "thermally compensated";
      case 2:
        return "sensor calibrated";
      case 3:
        return "fully calibrated";
      default:
        return "undefined";
    }
  }
  return mode == 0 ? "raw" : mode == 1 ? "surface" : "undefined";
}

UnitModeReading ReadUnitMode(const UnitPort& port, const Clock& clock) {
  const OpenUnit unit = Identify(port, clock);
  return {unit.identity.unit_kind, unit.identity, -1, 0};
}

UnitModeReading SetUnitMode(const UnitPort& port,
                            uint8_t mode,
                            const Clock& clock,
                            int packets,
                            std::chrono::milliseconds packet_wait) {
  OpenUnit unit = Identify(port, clock);
  const UnitKind kind = unit.identity.unit_kind;
  if (kind == UnitKind::kImu) {
    unit.link->SetImuMode(static_cast<fm::ImuCompensationMode>(mode));
  } else {
    unit.link->SetAdsMode(static_cast<fm::AdsCompensationMode>(mode));
  }
  UnitModeReading reading{kind, unit.link->Identify(), -1, 0};
  const std::string command = fmt::format("SET_MODE {}", mode);
  if (reading.identity.mode != mode) {
    Fail(port,
         Kind::kWrongIdentity,
         command,
         fmt::format("acknowledged, but IDENTIFY reads back mode {}", reading.identity.mode));
  }
  // Everything after the IDENTIFY answer was sent in the new mode.
  unit.link->RestartStream();
  const auto deadline = std::chrono::steady_clock::now() + packet_wait;
  while (reading.packets_checked < packets) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      Fail(port,
           Kind::kNoReply,
           command,
           fmt::format("{} of {} data packets within {} ms after the change",
                       reading.packets_checked,
                       packets,
                       packet_wait.count()));
    }
    for (const ReceivedPacket& packet : unit.link->Poll(left)) {
      reading.packet_mode = PacketMode(packet);
      if (reading.packet_mode != mode) {
        Fail(port,
             Kind::kWrongIdentity,
             command,
             fmt::format("a data packet after the change carries mode {}", reading.packet_mode));
      }
      ++reading.packets_checked;
    }
  }
  return reading;
}

}  // namespace adahrs::hil
