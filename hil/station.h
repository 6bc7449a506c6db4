// The station file (docs/station.md): which serial port holds which instrument and which unit, and
// how fast the lab's clock runs. It is the only thing that differs between the virtual rig and the
// real lab: the pipeline reads it and nothing else about where its instruments are.
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

struct InstrumentEntry {
  std::string role;  ///< "rate_table", "imu_chamber", "ads_chamber", "adts"
  InstrumentType type{};
  SerialSettings port;
  int address = 0;        ///< Modbus slave address (F4), controller address (942), GPIB (ADTS)
  int timeout_ms = 1000;  ///< per reply, wall-clock milliseconds at time scale 1
  int retries = 2;        ///< bounded retries of an unanswered command
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
  OperatorEntry op;  ///< the console when the file has no "operator" entry

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
