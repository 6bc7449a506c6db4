// Air data test set driver: a Druck ADTS 405 on GPIB behind a Prologix GPIB-USB adapter
// (shared/protocols.md §4 and §6; docs/rig/adts.md), implementing AirDataTestSet.
// Adapter set-up, once before the first command (DOC, Prologix manual §8; the pyvisa-py recipe):
// `++mode 1` (controller), `++addr <address>`, `++auto 0` (no read-after-write: a query is followed
// by `++read eoi`), `++eos 2` (LF appended to data), `++eoi 1`, `++eot_enable 0`; then `*CLS` and
// `UNIT:PRES PA` so every pressure is in pascals. Data lines are ESC-escaped
// (hil/codecs/prologix.h). SCPI (DRV unless noted; numbers by hil/codecs/scpi.h):
//   Identify      `++ver`, `*IDN?` (must name an ADTS, else kWrongIdentity)
//   SetAltitude   `SOUR:STAT ON`, `SOUR:RATE ALT,<ft/min>`, `SOUR:PRES ALT,<ft>`
//   SetAirspeed   `SOUR:STAT ON`, `SOUR:RATE CAS,<kt/min>`, `SOUR:PRES CAS,<kt>`
//   Stable        `STAT:OPER:COND?`: bits 1 (stable at aim, 15 s after 8 and 10), 8 (Ps at set
//                 point) and 10 (Pt at set point) all set (§4.4). The condition register, not
//                 `STAT:OPER:EVEN?`: the event register is latched and cleared on read, so a poll
//                 would see a stale "stable" from an earlier aim.
//   Read          `MEAS:PRES? PS`, `MEAS:PRES? QC`
//   GoToGround    `SOUR:STAT ON`, `SOUR:GTGR` (needs control mode)
// Every command that returns nothing is followed by `SYST:ERR?` (INF: the 405's error queue format
// is UNKNOWN; `<code>,"<message>"` here): a non-zero code becomes kRefused with that text.
// Replies end in LF; timeouts and retries are the station entry's (instrument_port.h).
// Left out: Mach/EPR/TAS aims, altitude and speed unit commands (UNKNOWN; ft and kt assumed),
// leak tests, limit sets, service requests.
#pragma once

#include <string>

#include "hil/drivers/instrument_port.h"
#include "hil/instruments/instruments.h"

namespace adahrs::hil {

/// STAT:OPER:COND? bits (protocols.md §4.4, DRV).
inline constexpr int kAdtsStableBit = 1;
inline constexpr int kAdtsPsAtSetPointBit = 8;
inline constexpr int kAdtsPtAtSetPointBit = 10;

class AdtsPrologix : public AirDataTestSet {
 public:
  AdtsPrologix(const InstrumentEntry& entry, const Clock& clock);

  InstrumentIdentity Identify() override;
  void SetAltitude(double alt_ft, double rate_ft_per_min) override;
  void SetAirspeed(double cas_kt, double rate_kt_per_min) override;
  bool Stable() override;
  AirDataReading Read() override;
  void GoToGround() override;

 private:
  void Configure();
  // A SCPI command without a reply, checked with SYST:ERR?.
  void Command(const std::string& scpi);
  std::string Query(const std::string& scpi);
  double QueryNumber(const std::string& scpi);

  InstrumentPort port_;
  bool configured_ = false;
};

}  // namespace adahrs::hil
