// IMU thermal-chamber driver: a Watlow Series F4 ramping controller on Modbus RTU, with libmodbus
// as the master (modbus_new_rtu on the station's port, slave = the entry's address), implementing
// Chamber. Registers as shared/protocols.md §2.3-2.5 give them (DRV; docs/rig/watlow-f4.md lists
// what the virtual F4 does with each):
//   Identify        901 (units: 1 = degC, else kWrongIdentity), 606 (implied decimals)
//   ReadProcessC    100 PV and 101 input error (non-zero: kFault)
//   SetSetPointC    300 static set point (signed, `decimals` implied decimals)
//   ReadSetPointC   4122 current set point (a running profile's ramp, or 300 when static)
//   Hold            200 (2 running, 3 holding) → 4122 read, 1217 = 1 (terminate), 300 = that set
//   point DownloadProfile names 3500+10(n-1); an existing profile of that name deleted (4000 = n,
//                   4001 = 1, 4002 = 3) and its name blanked; 4002 = 1 create, 4000 read back;
//                   name written; per step FC16 4001 = [i, 2] (insert), 4003 type, then 4009-4011
//                   h/m/s, 4043 rate x10, 4044 target, 4050-4052 jump; the end step 4003 = 5,
//                   4060/4061; 25 = 0 (save)
//   StartProfile    4000 = n, 4001 = 1, 4002 = 5;  ProfileRunning: 200 is 2 or 3
// Durations are whole seconds (F4 resolution, rounded to nearest), at most 99:59:59 per step.
// A Modbus exception becomes kRefused naming the register and the exception code; a timeout is
// retried `retries` times, then kNoReply. Response timeout: the entry's, scaled by the clock
// (instrument_port.h).
// Left out: guaranteed soak, events, wait-fors, PID sets, autostart; the model/serial registers 0-4
// (the virtual F4 does not map them; their values are UNKNOWN).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hil/clock.h"
#include "hil/instruments/instrument_error.h"
#include "hil/instruments/instruments.h"
#include "hil/station.h"

struct _modbus;

namespace adahrs::hil {

class WatlowF4Chamber : public Chamber {
 public:
  WatlowF4Chamber(const InstrumentEntry& entry, const Clock& clock);
  ~WatlowF4Chamber() override;
  WatlowF4Chamber(const WatlowF4Chamber&) = delete;
  WatlowF4Chamber& operator=(const WatlowF4Chamber&) = delete;

  InstrumentIdentity Identify() override;
  void SetSetPointC(double temp_c) override;
  double ReadSetPointC() override;
  double ReadProcessC() override;
  void Hold() override;

  bool SupportsProfiles() const override { return true; }
  void DownloadProfile(const std::string& name, const std::vector<F4ProfileStep>& steps) override;
  void StartProfile(const std::string& name) override;
  bool ProfileRunning() override;

 private:
  std::vector<uint16_t> Read(uint16_t reg, int count);
  void Write(uint16_t reg, uint16_t value);
  void WriteMany(uint16_t reg, const std::vector<uint16_t>& values);
  // Runs one libmodbus call with retries on timeout; maps failures to InstrumentError.
  template <typename Call>
  void Transact(const std::string& command, Call call);

  int Decimals();
  uint16_t ToRegister(double temp_c, const std::string& what);
  double FromRegister(uint16_t value);
  // Profile numbers (1-based) whose name register block holds `name` (padded).
  std::vector<int> FindProfiles(const std::string& padded_name);
  [[noreturn]] void Fail(InstrumentError::Kind kind,
                         const std::string& command,
                         const std::string& reply,
                         const std::string& detail) const;

  InstrumentEntry entry_;
  const Clock& clock_;
  _modbus* ctx_ = nullptr;
  int decimals_ = -1;  // read from 606 on first use
  std::map<std::string, int> profile_numbers_;
};

}  // namespace adahrs::hil
