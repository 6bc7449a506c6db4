// What the executor asks of the lab's instruments, whatever protocol speaks it: one abstract class
// per instrument role. The drivers (hil/drivers/) implement them over SerialPort and the protocol
// codecs (hil/codecs/); the executor (calib/executor/) only ever sees these classes, so a virtual
// rig and a real lab are the same to it.
// Every call is synchronous, bounded by the driver's timeout and retries, and throws
// InstrumentError (instrument_error.h) naming the role, the port, the command and the reply.
// Units: deg/s and deg/s^2 (table), degC (chamber), ft, ft/min, kt, kt/min and Pa (air data).
// Left out: position mode and sine motion of the table, chamber humidity, ADTS Mach/EPR aims.
#pragma once

#include <string>
#include <vector>

#include "hil/instruments/f4_profile.h"

namespace adahrs::hil {

/// What an instrument says it is, for the pre-flight table and meta.json.
struct InstrumentIdentity {
  std::string model;   ///< e.g. "Watlow F4", "Druck ADTS 405", "Aerosmith ATL"
  std::string detail;  ///< serial number, software version, whatever the instrument reports
};

class RateTable {
 public:
  virtual ~RateTable() = default;
  virtual InstrumentIdentity Identify() = 0;
  /// Rate mode at `rate_dps`, ramped at `accel_dps2`; the table refuses rates beyond its limit.
  virtual void CommandRate(double rate_dps, double accel_dps2) = 0;
  /// Measured platter rate, deg/s.
  virtual double ReadRateDps() = 0;
  /// True when the controller reports the commanded rate reached and steady.
  virtual bool AtRate() = 0;
  /// Decelerates to rest at `accel_dps2` (the safe state).
  virtual void Stop(double accel_dps2) = 0;
};

class Chamber {
 public:
  virtual ~Chamber() = default;
  virtual InstrumentIdentity Identify() = 0;
  virtual void SetSetPointC(double temp_c) = 0;
  virtual double ReadSetPointC() = 0;
  /// Process value (chamber air as the controller measures it), degC.
  virtual double ReadProcessC() = 0;
  /// Safe state: any running profile stopped, the present set point held.
  virtual void Hold() = 0;

  /// Whether the controller stores and runs ramping profiles (F4: yes; 942 driver: no).
  virtual bool SupportsProfiles() const = 0;
  /// Writes `steps` as profile `name` (replacing a profile of that name); throws kRefused when the
  /// controller has no profiles.
  virtual void DownloadProfile(const std::string& name,
                               const std::vector<F4ProfileStep>& steps) = 0;
  virtual void StartProfile(const std::string& name) = 0;
  /// True while the profile started last is running (not yet at its end step).
  virtual bool ProfileRunning() = 0;
};

struct AirDataReading {
  double ps_pa = 0.0;  ///< static pressure the test set measures
  double qc_pa = 0.0;  ///< impact pressure (Pt - Ps) the test set measures
};

class AirDataTestSet {
 public:
  virtual ~AirDataTestSet() = default;
  virtual InstrumentIdentity Identify() = 0;
  /// Control mode on; aims the static port at pressure altitude `alt_ft` at `rate_ft_per_min`.
  virtual void SetAltitude(double alt_ft, double rate_ft_per_min) = 0;
  /// Aims the pitot port at calibrated airspeed `cas_kt` at `rate_kt_per_min`.
  virtual void SetAirspeed(double cas_kt, double rate_kt_per_min) = 0;
  /// True when the test set reports both channels at their aims and stable (a condition, not a
  /// latched event).
  virtual bool Stable() = 0;
  virtual AirDataReading Read() = 0;
  /// Safe state: back to ground (vented, Qc 0) at safe rates.
  virtual void GoToGround() = 0;
};

/// The operator's side of the fixture: mounting the batch in an orientation and answering prompts.
/// On the real lab a person at the console; in simulation the rig's virtual fixture.
class Operator {
 public:
  virtual ~Operator() = default;
  /// Mounts the units of `unit_roles` (e.g. "imu1") in fixture orientation `orientation_code`
  /// (11…32) and returns when the operator confirms.
  virtual void Mount(const std::vector<std::string>& unit_roles, int orientation_code) = 0;
  /// Shows `text` and returns when the operator has acted; throws InstrumentError (kRefused) when
  /// the operator aborts.
  virtual void Prompt(const std::string& text) = 0;
};

}  // namespace adahrs::hil
