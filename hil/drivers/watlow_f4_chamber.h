// IMU thermal-chamber driver: a Watlow Series F4 ramping controller on Modbus RTU, with libmodbus
// as the master (modbus_new_rtu on the station's port, slave = the entry's address), implementing
// Chamber. Registers as shared/protocols.md §2.3-2.5 give them (DRV; docs/rig/watlow-f4.md lists
// what the virtual F4 does with each): identify 901/606, PV 100 and input error 101, static set
// point 300, current set point 4122, status 200, profiles at 3500+10(n-1) and 4000-4061.
// A Modbus exception becomes kRefused naming the register and the exception code; a timeout is
// retried `retries` times, then kNoReply (timeouts: instrument_port.h).
// Units: degC as signed registers with register 606's implied decimals; step durations in whole
// seconds (at most 99:59:59); ramp rates in 0.1 degC/min.
// Every method's registers: docs/drivers.md ("IMU chamber").
// Left out: guaranteed soak, events, wait-fors, PID sets, autostart; the model/serial registers
// 0-4 (the virtual F4 does not map them; their values are UNKNOWN).
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
