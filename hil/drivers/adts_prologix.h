// Air data test set driver: a Druck ADTS 405 on GPIB behind a Prologix GPIB-USB adapter
// (shared/protocols.md §4 and §6; docs/rig/adts.md), implementing AirDataTestSet. The adapter is
// set up once (controller mode, no read-after-write, LF appended), then `*CLS` and `UNIT:PRES PA`;
// data lines are ESC-escaped (hil/codecs/prologix.h), numbers by hil/codecs/scpi.h. Stable polls
// `STAT:OPER:COND?` bits 1, 8 and 10 (the condition register, not the latched event register);
// every command without a reply is followed by `SYST:ERR?`, a non-zero code becoming kRefused.
// Units: pressures in Pa, altitude aims in ft and ft/min, airspeed aims in kt CAS and kt/min.
// Every command with its confidence label: docs/drivers.md ("Air data test set"); timeouts and
// retries: the station entry's (instrument_port.h, docs/drivers.md "Timeouts and retries").
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
