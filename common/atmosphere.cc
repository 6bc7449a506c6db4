#include "common/atmosphere.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace adahrs::common {
namespace {

// g0/(R·L) = 5.255880 (physics.md §4.1).
const double kTroposphereExponent =
    common::kStandardGravity_mps2 / (kIsaGasConstant_j_per_kg_k * kIsaLapseRate_k_per_m);
const double kTropopauseTemperature_k =
    kIsaSeaLevelTemperature_k - kIsaLapseRate_k_per_m * kIsaTropopauseAltitude_m;
const double kTropopausePressure_pa =
    kIsaSeaLevelPressure_pa *
    std::pow(kTropopauseTemperature_k / kIsaSeaLevelTemperature_k, kTroposphereExponent);
// R·T11/g0 = 6341.62 m (physics.md §4.1).
const double kStratosphereScaleHeight_m =
    kIsaGasConstant_j_per_kg_k * kTropopauseTemperature_k / common::kStandardGravity_mps2;

[[noreturn]] void ThrowOutOfRange(const char* function,
                                  const char* name,
                                  double value,
                                  double min,
                                  double max,
                                  const char* unit) {
  std::ostringstream message;
  message << function << ": " << name << " = " << value << " " << unit
          << " is outside the modelled ISA range [" << min << ", " << max << "] " << unit;
  throw std::domain_error(message.str());
}

void CheckAltitude(const char* function, double alt_m) {
  if (!(alt_m >= kIsaMinAltitude_m && alt_m <= kIsaMaxAltitude_m)) {
    ThrowOutOfRange(function, "alt_m", alt_m, kIsaMinAltitude_m, kIsaMaxAltitude_m, "m");
  }
}

double PressureAt(double alt_m) {
  if (alt_m <= kIsaTropopauseAltitude_m) {
    return kIsaSeaLevelPressure_pa *
           std::pow(1.0 - kIsaLapseRate_k_per_m * alt_m / kIsaSeaLevelTemperature_k,
                    kTroposphereExponent);
  }
  return kTropopausePressure_pa *
         std::exp(-(alt_m - kIsaTropopauseAltitude_m) / kStratosphereScaleHeight_m);
}

}  // namespace

double IsaStaticPressurePa(double alt_m) {
  CheckAltitude("IsaStaticPressurePa", alt_m);
  return PressureAt(alt_m);
}

double IsaTemperatureK(double alt_m) {
  CheckAltitude("IsaTemperatureK", alt_m);
  if (alt_m <= kIsaTropopauseAltitude_m) {
    return kIsaSeaLevelTemperature_k - kIsaLapseRate_k_per_m * alt_m;
  }
  return kTropopauseTemperature_k;
}

double IsaPressureAltitudeM(double ps_pa) {
  const double max_pa = PressureAt(kIsaMinAltitude_m);
  const double min_pa = PressureAt(kIsaMaxAltitude_m);
  if (!(ps_pa >= min_pa && ps_pa <= max_pa)) {
    ThrowOutOfRange("IsaPressureAltitudeM", "ps_pa", ps_pa, min_pa, max_pa, "Pa");
  }
  if (ps_pa >= kTropopausePressure_pa) {
    // h = (T0/L)·[1 − (p/p0)^(1/5.25588)]
    return kIsaSeaLevelTemperature_k / kIsaLapseRate_k_per_m *
           (1.0 - std::pow(ps_pa / kIsaSeaLevelPressure_pa, 1.0 / kTroposphereExponent));
  }
  // h = 11 000 m − H·ln(p/p11)
  return kIsaTropopauseAltitude_m -
         kStratosphereScaleHeight_m * std::log(ps_pa / kTropopausePressure_pa);
}

double IsaStaticPressurePaFromFt(double alt_ft) {
  if (!(common::FtToM(alt_ft) >= kIsaMinAltitude_m && common::FtToM(alt_ft) <= kIsaMaxAltitude_m)) {
    ThrowOutOfRange("IsaStaticPressurePaFromFt",
                    "alt_ft",
                    alt_ft,
                    common::MToFt(kIsaMinAltitude_m),
                    common::MToFt(kIsaMaxAltitude_m),
                    "ft");
  }
  return PressureAt(common::FtToM(alt_ft));
}

double IsaPressureAltitudeFt(double ps_pa) { return common::MToFt(IsaPressureAltitudeM(ps_pa)); }

double SpeedOfSoundMps(double static_temp_k) {
  if (!(static_temp_k > 0.0 && std::isfinite(static_temp_k))) {
    std::ostringstream message;
    message << "SpeedOfSoundMps: static_temp_k = " << static_temp_k
            << " K is not a positive finite temperature";
    throw std::domain_error(message.str());
  }
  return std::sqrt(kIsaHeatCapacityRatio * kIsaGasConstant_j_per_kg_k * static_temp_k);
}

}  // namespace adahrs::common
