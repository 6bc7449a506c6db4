// A unit's firmware output mode over its maintenance port, for `adahrs unit mode`
// (docs/unit-protocol.md §4.1, §5.1, §6): the unit on a bare port is identified (its kind learnt
// from its IDENTIFY answer or its data packets, no station file needed), its mode read; a new mode
// is sent with SET_MODE, read back with IDENTIFY, and the first data packets after it are checked
// to carry the new mode. Modes: IMU 0 raw, 1 thermally compensated, 2 sensor calibrated, 3 fully
// calibrated; ADS 0 raw, 1 surface. The unit refuses a mode it does not define (NAK bad argument)
// and any calibrated mode without committed constants (NAK no valid constants).
// Errors: InstrumentError naming the port: kNoReply (port absent, or no answer after retries),
// kRefused (the unit's NAK), kBadReply, kWrongIdentity (a mode read back or streamed other than
// the one set). Left out: the mode's persistence (the unit powers up raw).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "hil/clock.h"
#include "hil/codecs/unit_protocol_client.h"
#include "hil/station.h"

namespace adahrs::hil {

/// The unit's name of `mode` for its kind ("raw", "fully calibrated", ...; "undefined" if none).
std::string UnitModeName(UnitKind kind, uint8_t mode);

struct UnitModeReading {
  UnitKind kind{};
  IdentifyInfo identity{};  ///< the last IDENTIFY answer (mode, serial, constants)
  /// Set by SetUnitMode: the mode byte of the first data packets after the change and how many
  /// were checked.
  int packet_mode = -1;
  int packets_checked = 0;
};

/// Where and how to reach the unit: `port.baud` the unit's line (115,200 on the units),
/// `timeout_ms` one request attempt's wait.
struct UnitPort {
  SerialSettings port;
  int timeout_ms = 500;
};

/// IDENTIFY on the unit at `port`.
UnitModeReading ReadUnitMode(const UnitPort& port, const Clock& clock);

/// SET_MODE `mode`, IDENTIFY to read it back, then data packets until `packets` of the new
/// format arrived (within `packet_wait` of wall time); throws as the header says.
UnitModeReading SetUnitMode(const UnitPort& port,
                            uint8_t mode,
                            const Clock& clock,
                            int packets = 5,
                            std::chrono::milliseconds packet_wait = std::chrono::seconds(5));

}  // namespace adahrs::hil
