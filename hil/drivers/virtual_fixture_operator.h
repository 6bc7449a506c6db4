// The operator of a simulated run: the virtual rig's fixture, reached through the rig's control
// port (role "control", docs/rig.md "Control port"). Mount() sends `orientation <imu role> <code>`
// for each unit and requires the reply `OK <imu role> <code>`; Prompt() logs the text and returns
// at once (nobody is there to act; the rig needs no action beyond what the executor commands).
// Replies are awaited kControlReplyTimeoutS of clock time (floor kMinWallReplyTimeout of wall).
// Errors: InstrumentError with role "operator", the control port, the command line and the reply.
// Left out: every other control-port command (faults, env) — test tools, not an operator's job.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "hil/clock.h"
#include "hil/instruments/instruments.h"
#include "hil/station.h"
#include "hil/transport/serial_port.h"

namespace adahrs::hil {

/// The control port answers at the next 10 ms frame; 2 s of clock time is generous.
inline constexpr double kControlReplyTimeoutS = 2.0;

class VirtualFixtureOperator : public Operator {
 public:
  /// Opens the control port of `entry` (type kVirtualFixture); prompts are logged to `log`.
  VirtualFixtureOperator(const OperatorEntry& entry, const Clock& clock, std::ostream& log);

  void Mount(const std::vector<std::string>& unit_roles, int orientation_code) override;
  void Prompt(const std::string& text) override;

 private:
  std::string Command(const std::string& line);

  const Clock& clock_;
  std::ostream& log_;
  std::unique_ptr<SerialPort> port_;
};

}  // namespace adahrs::hil
