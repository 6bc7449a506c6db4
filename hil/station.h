// The station file (docs/station.md): which serial port holds which instrument and which unit,
// what each instrument can take, and how fast the lab's clock runs. It is the only thing that
// differs between the virtual rig and the real lab: the pipeline reads it and nothing else about
// where its instruments are.
// Every key is validated (ParamReader): a wrong key, a missing port, a baud rate the instrument
// cannot use, a duplicate port or role are refused with the file and JSON path.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/param_reader.h"
#include "common/unit_kind.h"
#include "hil/transport/serial_port.h"

namespace adahrs::hil {

enum class InstrumentType { kAerosmithAtl, kWatlowF4, kWatlow942, kDruckAdtsPrologix };

/// What an instrument can take, as the station declares it (docs/station.md "Limits"). Each is
/// optional: a limit the file leaves out is the pipeline's default (calib/sequence/
/// sequence_limits.h, converted in calib/sequence/station_limits.h). Which keys an entry may hold
/// depends on its role: rate table max_rate_dps, max_accel_dps2; chambers min_c, max_c,
/// max_ramp_c_per_min, heat_rate_c_per_min, cool_rate_c_per_min; ADTS ps_min_pa, ps_max_pa,
/// qc_max_pa, max_alt_rate_ft_per_min, max_cas_rate_kt_per_min.
struct InstrumentLimits {
  std::optional<double> max_rate_dps;         ///< rate table: highest |rate| it is commanded to
  std::optional<double> max_accel_dps2;       ///< rate table: highest acceleration setting
  std::optional<double> min_c;                ///< chamber: lowest set point
  std::optional<double> max_c;                ///< chamber: highest set point
  std::optional<double> max_ramp_c_per_min;   ///< chamber: fastest ramp its air follows
  std::optional<double> heat_rate_c_per_min;  ///< chamber: how fast its air heats to a set point
  std::optional<double> cool_rate_c_per_min;  ///< chamber: how fast its air cools to a set point
  std::optional<double> ps_min_pa;            ///< ADTS: static pressure range (absolute)
  std::optional<double> ps_max_pa;
  std::optional<double> qc_max_pa;  ///< ADTS: highest impact pressure Pt − Ps
  std::optional<double> max_alt_rate_ft_per_min;
  std::optional<double> max_cas_rate_kt_per_min;
};

struct InstrumentEntry {
  std::string role;  ///< "rate_table", "imu_chamber", "ads_chamber", "adts"
  InstrumentType type{};
  SerialSettings port;
  int address = 0;          ///< Modbus slave address (F4), controller address (942), GPIB (ADTS)
  int timeout_ms = 1000;    ///< per reply, wall-clock milliseconds at time scale 1
  int retries = 2;          ///< bounded retries of an unanswered command
  InstrumentLimits limits;  ///< the entry's optional "limits" object
};

using common::UnitKind;

struct UnitEntry {
  std::string role;  ///< "imu1" … "imu4", "ads1" …
  UnitKind kind{};
  SerialSettings port;
  int slot = 0;  ///< fixture slot (IMU) or pneumatic manifold position (ADS), 1-based
  int timeout_ms = 500;
};

/// Who mounts the units and answers prompts (docs/station.md "operator").
enum class OperatorType {
  kConsole,         ///< a person at the PC's console: text on stdout, Enter on stdin
  kVirtualFixture,  ///< the virtual rig's control port (`orientation <imu role> <code>`)
};

struct OperatorEntry {
  OperatorType type = OperatorType::kConsole;
  SerialSettings port;  ///< kVirtualFixture only: the rig's control port
};

/// The executor's interlock thresholds and attempts as the station sets them (docs/station.md
/// "Interlocks"); each optional, unset keeps the executor's default (calib/executor/interlocks.h).
struct InterlockSettings {
  std::optional<double> relative_tolerance_g;  ///< gravity check against the last passed one, g
  std::optional<double> first_check_margin_g;  ///< a unit's first gravity check, g
  std::optional<double> min_gyro_response;     ///< gyro check: response / nominal, lowest
  std::optional<double> max_gyro_response;     ///< gyro check: response / nominal, highest
  std::optional<int> attempts;                 ///< tries (a prompt between) before the run stops
};

struct Station {
  std::string name;
  double time_scale = 1.0;  ///< clock seconds per wall second (1 on a real lab)
  /// A lockstep virtual rig's clock file (hil/rig_clock.h); empty: the clock is the wall's,
  /// scaled by time_scale.
  std::string clock_file;
  double latitude_deg = 0.0;
  double height_m = 0.0;
  double local_gravity_mps2 = 0.0;  ///< WGS-84 normal gravity at latitude and height
  std::vector<InstrumentEntry> instruments;
  std::vector<UnitEntry> units;
  OperatorEntry op;              ///< the console when the file has no "operator" entry
  InterlockSettings interlocks;  ///< the file's optional "interlocks" object

  /// Loads and validates a station file; throws common::ParamError naming file and path.
  static Station Load(const std::string& file_path);
  static Station FromJson(const common::ParamReader& reader);
  nlohmann::json ToJson() const;

  /// The instrument in `role`, if the station has one.
  const InstrumentEntry* Instrument(const std::string& role) const;
};

std::string ToString(InstrumentType type);
std::string ToString(OperatorType type);

}  // namespace adahrs::hil
