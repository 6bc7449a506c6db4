#include "calib/sequence/station_limits.h"

#include <algorithm>
#include <optional>

#include "common/air_data.h"
#include "common/atmosphere.h"

namespace adahrs::calib {
namespace {

void Take(double& field, const std::optional<double>& declared) {
  if (declared) field = *declared;
}

// Pressure altitude of `ps_pa`, at the end of the ISA model when the pressure lies beyond it (the
// validator refuses aims outside the model on its own).
double AltitudeFt(double ps_pa) {
  const double lowest_pa = common::IsaStaticPressurePa(common::kIsaMaxAltitude_m);
  const double highest_pa = common::IsaStaticPressurePa(common::kIsaMinAltitude_m);
  return common::IsaPressureAltitudeFt(std::clamp(ps_pa, lowest_pa, highest_pa));
}

// Calibrated airspeed of `qc_pa`, at most a0 (the subsonic relation's end; supersonic aims are
// beyond the unit's 450 kt anyway).
double AirspeedKt(double qc_pa) {
  const double qc_a0_pa = common::ImpactPressurePa(common::SeaLevelSpeedOfSoundMps());
  return common::CalibratedAirspeedKt(std::min(qc_pa, qc_a0_pa));
}

}  // namespace

SequenceLimits LimitsForStation(const hil::Station& station) {
  SequenceLimits limits;
  for (const hil::InstrumentEntry& e : station.instruments) {
    const hil::InstrumentLimits& l = e.limits;
    switch (e.type) {
      case hil::InstrumentType::kAerosmithAtl:
        Take(limits.table_max_rate_dps, l.max_rate_dps);
        Take(limits.table_max_accel_dps2, l.max_accel_dps2);
        break;
      case hil::InstrumentType::kWatlowF4:
        Take(limits.chamber_min_c, l.min_c);
        Take(limits.chamber_max_c, l.max_c);
        Take(limits.chamber_max_ramp_c_per_min, l.max_ramp_c_per_min);
        break;
      case hil::InstrumentType::kWatlow942:
        Take(limits.ads_chamber_min_c, l.min_c);
        Take(limits.ads_chamber_max_c, l.max_c);
        Take(limits.ads_chamber_max_ramp_c_per_min, l.max_ramp_c_per_min);
        break;
      case hil::InstrumentType::kDruckAdtsPrologix:
        // The lowest static pressure is the highest altitude.
        if (l.ps_min_pa) limits.adts_alt_max_ft = AltitudeFt(*l.ps_min_pa);
        if (l.ps_max_pa) limits.adts_alt_min_ft = AltitudeFt(*l.ps_max_pa);
        if (l.qc_max_pa) limits.adts_cas_max_kt = AirspeedKt(*l.qc_max_pa);
        Take(limits.adts_max_alt_rate_ft_per_min, l.max_alt_rate_ft_per_min);
        Take(limits.adts_max_cas_rate_kt_per_min, l.max_cas_rate_kt_per_min);
        break;
    }
  }
  return limits;
}

PlanTiming TimingForStation(const hil::Station& station, UnitKind kind, PlanTiming base) {
  if (station.op.type == hil::OperatorType::kVirtualFixture) base.operator_prompt_s = 0.0;
  const hil::InstrumentEntry* chamber =
      station.Instrument(kind == UnitKind::kImu ? "imu_chamber" : "ads_chamber");
  if (chamber != nullptr) {
    if (chamber->limits.heat_rate_c_per_min)
      base.chamber_heat_c_per_min = chamber->limits.heat_rate_c_per_min;
    if (chamber->limits.cool_rate_c_per_min)
      base.chamber_cool_c_per_min = chamber->limits.cool_rate_c_per_min;
  }
  return base;
}

}  // namespace adahrs::calib
