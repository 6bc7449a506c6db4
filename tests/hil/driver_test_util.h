// Shared pieces of the instrument-driver tests: a rig process, its station and a scaled clock, and
// bounded waits on a condition polled through a driver (wall-clock limits, never fixed sleeps).
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "../support/rig_process.h"
#include "hil/drivers/station_instruments.h"

namespace adahrs::hil::test {

/// 200 simulated s per wall s: minutes of chamber and ADTS settling take a second of wall time.
inline constexpr double kTimeScale = 200.0;

struct RigStation {
  testing::RigProcess rig{kTimeScale};
  Station station = Station::Load(rig.WriteStation());
  ScaledClock clock{kTimeScale};
  const InstrumentEntry& Entry(const std::string& role) const { return *station.Instrument(role); }
};

/// Polls `condition` every simulated second until it holds or `wall_limit` passes; true if held.
inline bool WaitUntil(const Clock& clock,
                      const std::function<bool()>& condition,
                      std::chrono::milliseconds wall_limit = std::chrono::seconds(10)) {
  const auto end = std::chrono::steady_clock::now() + wall_limit;
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    clock.SleepS(1.0);
  }
  return false;
}

/// A value from the rig's `env` control reply ("… key=value …").
inline double EnvValue(const testing::RigProcess& rig, const std::string& key) {
  const std::string env = rig.Control("env");
  const size_t at = env.find(" " + key + "=");
  if (at == std::string::npos) throw std::runtime_error("no " + key + " in " + env);
  return std::stod(env.substr(at + key.size() + 2));
}

}  // namespace adahrs::hil::test
