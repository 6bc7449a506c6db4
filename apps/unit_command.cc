// adahrs unit mode --port P [--set N] [--baud B] [--timeout-ms T]: reads a unit's firmware mode
// over its maintenance port, or sets it, reads it back and checks the data packets that follow
// (hil/drivers/unit_mode.h; modes in docs/unit-protocol.md §4.1, §5.1). No station file: the
// unit's kind comes from its own answer.
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "apps/commands.h"
#include "common/unit_kind.h"
#include "hil/clock.h"
#include "hil/drivers/unit_mode.h"

namespace adahrs::apps {
namespace {

struct ModeOptions {
  std::string port;
  std::optional<int> set;
  unsigned baud = 115200;
  int timeout_ms = 500;
};

std::string Describe(const hil::UnitModeReading& r) {
  const hil::IdentifyInfo& id = r.identity;
  return fmt::format("{} serial {} firmware {}.{}.{}, constants {}: mode {} ({})",
                     common::UnitKindName(r.kind),
                     id.serial_number,
                     id.firmware_major,
                     id.firmware_minor,
                     id.firmware_patch,
                     id.constants_valid ? fmt::format("committed (version {}, crc 0x{:04x})",
                                                      id.constants_version,
                                                      id.constants_crc)
                                        : std::string("none committed"),
                     id.mode,
                     hil::UnitModeName(r.kind, id.mode));
}

void RegisterMode(CLI::App* unit) {
  CLI::App* cmd = unit->add_subcommand(
      "mode",
      "Read a unit's firmware mode, or set it (IMU 0 raw, 1 thermal, 2 sensor calibrated, "
      "3 fully calibrated; ADS 0 raw, 1 surface)");
  auto o = std::make_shared<ModeOptions>();
  cmd->add_option("--port", o->port, "The unit's serial port")->required();
  cmd->add_option("--set", o->set, "Mode to set, read back and check in the data packets")
      ->check(CLI::Range(0, 3));
  cmd->add_option("--baud", o->baud, "Line speed")->capture_default_str();
  cmd->add_option("--timeout-ms", o->timeout_ms, "Wait for one reply attempt")
      ->check(CLI::Range(10, 60000))
      ->capture_default_str();
  cmd->callback([o] {
    const std::unique_ptr<hil::Clock> clock = hil::MakeClock(1.0);
    hil::UnitPort port;
    port.port.path = o->port;
    port.port.baud = o->baud;
    port.timeout_ms = o->timeout_ms;
    if (!o->set) {
      const std::string read = Describe(hil::ReadUnitMode(port, *clock));
      std::cout << o->port << ": " << read << "\n";
      return;
    }
    const hil::UnitModeReading r = hil::SetUnitMode(port, static_cast<uint8_t>(*o->set), *clock);
    std::cout << fmt::format("{}: {}; read back, {} data packets since in mode {}\n",
                             o->port,
                             Describe(r),
                             r.packets_checked,
                             r.packet_mode);
  });
}

}  // namespace

void RegisterUnitCommand(CLI::App& app) {
  CLI::App* unit = app.add_subcommand("unit", "A unit on its maintenance port");
  unit->require_subcommand(1);
  RegisterMode(unit);
}

}  // namespace adahrs::apps
