// Everything a station file names, opened: one driver per instrument role, one UnitLink per unit
// and the operator. The executor and `adahrs ports check` get their instruments only from here, so
// a virtual rig, socat relays and the real lab's /dev/ttyUSB* ports take the same code path.
// Opening a port does not talk to the instrument: identification is the caller's first command.
// Errors: InstrumentError naming the role and port that could not be opened.
#pragma once

#include <memory>
#include <vector>

#include "hil/clock.h"
#include "hil/drivers/unit_link.h"
#include "hil/instruments/instruments.h"
#include "hil/station.h"

namespace adahrs::hil {

struct StationInstruments {
  std::unique_ptr<RateTable> rate_table;  ///< null when the station has no rate_table
  std::unique_ptr<Chamber> imu_chamber;   ///< Watlow F4 (profiles)
  std::unique_ptr<Chamber> ads_chamber;   ///< Watlow 942
  std::unique_ptr<AirDataTestSet> adts;
  std::unique_ptr<Operator> op;                  ///< the station's "operator"; console if absent
  std::vector<std::unique_ptr<UnitLink>> units;  ///< station order
};

/// Opens every port of `station`; the drivers keep a reference to `clock`, which must outlive them.
StationInstruments OpenStation(const Station& station, const Clock& clock);

}  // namespace adahrs::hil
