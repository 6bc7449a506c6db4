// adahrs ports check --station FILE: the pre-flight table (hil/drivers/port_check.h) of every role
// of a station: role | port | identity | status. Exit status 1 if any role failed.
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "apps/commands.h"
#include "hil/clock.h"
#include "hil/drivers/port_check.h"
#include "hil/station.h"

namespace adahrs::apps {

void RegisterPortsCommand(CLI::App& app) {
  CLI::App* ports = app.add_subcommand("ports", "The station's serial ports");
  ports->require_subcommand(1);
  CLI::App* check = ports->add_subcommand(
      "check",
      "Identify every instrument and unit of a station; print role, port, identity, status");
  auto station_path = std::make_shared<std::string>();
  check->add_option("--station", *station_path, "Station JSON file (docs/station.md)")->required();
  check->callback([station_path] {
    const hil::Station station = hil::Station::Load(*station_path);
    const std::unique_ptr<hil::Clock> clock =
        hil::MakeClock(station.time_scale, station.clock_file);
    const std::vector<hil::PortCheckRow> rows = hil::CheckPorts(station, *clock);
    std::cout << fmt::format("{:<12} {:<32} {:<60} {}\n", "role", "port", "identity", "status");
    bool all_ok = true;
    for (const hil::PortCheckRow& row : rows) {
      std::cout << fmt::format("{:<12} {:<32} {:<60} {}\n",
                               row.role,
                               row.port,
                               row.identity.empty() ? "-" : row.identity,
                               row.ok ? "ok" : "FAILED: " + row.status);
      all_ok = all_ok && row.ok;
    }
    if (!all_ok) throw CLI::RuntimeError(1);
  });
}

}  // namespace adahrs::apps
