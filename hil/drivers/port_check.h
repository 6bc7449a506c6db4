// The pre-flight check of a station (`adahrs ports check`): every role opened on its own and asked
// who it is, so one dead port does not hide the state of the others. Instruments answer their
// driver's Identify(); units IDENTIFY (serial text, firmware, mode, constants version); the
// operator's port is only opened (neither a console nor the virtual fixture has an identity).
// A failure is a row with ok = false and the InstrumentError text, never an exception.
#pragma once

#include <string>
#include <vector>

#include "hil/clock.h"
#include "hil/station.h"

namespace adahrs::hil {

struct PortCheckRow {
  std::string role;
  std::string port;      ///< the device path, "console" for a console operator
  std::string identity;  ///< what answered; empty when nothing did
  bool ok = false;
  std::string status;  ///< "ok" or the error text
};

/// Checks every instrument, unit and the operator of `station`, in that order.
std::vector<PortCheckRow> CheckPorts(const Station& station, const Clock& clock);

}  // namespace adahrs::hil
