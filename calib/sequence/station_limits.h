// The one place a station file's declared instrument limits (hil::InstrumentLimits,
// docs/station.md "Limits") become the SequenceLimits a sequence is validated and planned against:
// the rate table's rate and acceleration, each chamber's set point range and ramp, the ADTS's
// pressure ranges (as altitude and airspeed by ISA, common/atmosphere.h and common/air_data.h) and
// rates; and the plan's timing from the chamber's declared heating and cooling rates. A limit the
// station leaves out keeps SequenceLimits' default; an instrument the station
// does not have keeps its defaults too (the executor refuses a step that needs it).
// Units as the fields name them (deg/s, deg/s^2, degC, degC/min, Pa, ft, kt, per minute).
// Left out: the unit limits (they belong to the unit, not the station), acquisition limits.
#pragma once

#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_limits.h"
#include "hil/station.h"

namespace adahrs::calib {

/// SequenceLimits' defaults with every limit `station` declares in their place.
SequenceLimits LimitsForStation(const hil::Station& station);

/// The plan's timing on `station` for a batch of `kind`: its chamber's (the F4 for IMUs, the 942
/// for ADS units) declared heating and cooling rates, and no operator time when the operator is
/// the virtual fixture; the rest as `base`.
PlanTiming TimingForStation(const hil::Station& station, UnitKind kind, PlanTiming base = {});

}  // namespace adahrs::calib
