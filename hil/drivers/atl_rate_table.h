// Rate-table driver: an Aerosmith 8xx controller speaking ATL over RS-232 (docs/rig/rate-table.md,
// shared/protocols.md §1), implementing RateTable. Commands are encoded by the codec's client
// encoder (hil/codecs/atl_codec.h) from AtlClientCommandTable(): CommandRate = `ACL a` + `JOG r`,
// Stop = `ACL a` + `STO`, ReadRateDps = `RAT?`, AtRate = bit 1 of `STA?`, Identify = `STA?` (ATL
// has no identification query). Each reply is read up to its `\r\n>\r\n` terminator; a reply
// whose data starts with '?' is a refusal (kRefused, the controller's text as the reply).
// JOG takes whole deg/s (DRV): a fractional rate is refused before anything is sent (kRefused),
// as is a rate or acceleration beyond the table's command limits.
// A status word with bit 4 (interlock open) makes AtRate throw kFault: the table cannot reach a
// rate until someone closes the door and re-enables the servo.
// The first command after opening leads with a line end: bytes another client left in the table's
// input without one (a station with swapped ports) form a line the table refuses first; that
// refusal is read and dropped, so the driver's first command is answered as if the line were clean.
// Timeouts and retries: the station entry's (instrument_port.h); a repeated JOG or STO is harmless.
// Left out: position mode, sine motion, servo control, echo (off in the lab's table).
#pragma once

#include <string>

#include "hil/drivers/instrument_port.h"
#include "hil/instruments/instruments.h"

namespace adahrs::hil {

/// STA? bits (UNKNOWN, invented with the command; rig_sim/data/atl_commands.json).
inline constexpr int kAtlStatusAtRateBit = 1;
inline constexpr int kAtlStatusInterlockOpenBit = 4;

class AtlRateTable : public RateTable {
 public:
  AtlRateTable(const InstrumentEntry& entry, const Clock& clock);

  InstrumentIdentity Identify() override;
  void CommandRate(double rate_dps, double accel_dps2) override;
  double ReadRateDps() override;
  bool AtRate() override;
  void Stop(double accel_dps2) override;

 private:
  // Sends one command and returns its reply data; throws kRefused for an error reply.
  std::string Command(const std::string& mnemonic, std::optional<double> argument, bool query);
  double QueryNumber(const std::string& mnemonic);
  int Status();

  InstrumentPort port_;
  /// Whether a command has ended any partial line a previous client left in the table's input.
  bool line_synced_ = false;
};

}  // namespace adahrs::hil
