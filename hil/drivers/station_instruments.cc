#include "hil/drivers/station_instruments.h"

#include <iostream>

#include "hil/drivers/adts_prologix.h"
#include "hil/drivers/atl_rate_table.h"
#include "hil/drivers/console_operator.h"
#include "hil/drivers/virtual_fixture_operator.h"
#include "hil/drivers/watlow942_chamber.h"
#include "hil/drivers/watlow_f4_chamber.h"

namespace adahrs::hil {

StationInstruments OpenStation(const Station& station, const Clock& clock) {
  StationInstruments out;
  // Each role holds one instrument type (station.cc refuses any other pairing).
  for (const InstrumentEntry& e : station.instruments) {
    switch (e.type) {
      case InstrumentType::kAerosmithAtl:
        out.rate_table = std::make_unique<AtlRateTable>(e, clock);
        break;
      case InstrumentType::kWatlowF4:
        out.imu_chamber = std::make_unique<WatlowF4Chamber>(e, clock);
        break;
      case InstrumentType::kWatlow942:
        out.ads_chamber = std::make_unique<Watlow942Chamber>(e, clock);
        break;
      case InstrumentType::kDruckAdtsPrologix:
        out.adts = std::make_unique<AdtsPrologix>(e, clock);
        break;
    }
  }
  if (station.op.type == OperatorType::kVirtualFixture) {
    out.op = std::make_unique<VirtualFixtureOperator>(station.op, clock, std::clog);
  } else {
    out.op = std::make_unique<ConsoleOperator>(std::cin, std::cout);
  }
  for (const UnitEntry& unit : station.units) {
    out.units.push_back(std::make_unique<UnitLink>(unit, clock, station.clock_file));
  }
  return out;
}

}  // namespace adahrs::hil
