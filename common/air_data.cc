#include "common/air_data.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/atmosphere.h"
#include "common/units.h"

namespace adahrs::common {
namespace {

// (γ−1)/2 = 0.2, γ/(γ−1) = 3.5, (γ−1)/γ = 2/7.
constexpr double kHalfGammaMinusOne = (kIsaHeatCapacityRatio - 1.0) / 2.0;
constexpr double kGammaOverGammaMinusOne = kIsaHeatCapacityRatio / (kIsaHeatCapacityRatio - 1.0);
constexpr double kGammaMinusOneOverGamma = (kIsaHeatCapacityRatio - 1.0) / kIsaHeatCapacityRatio;

// Pressure ratio pt/ps (or (qc + p0)/p0) at Mach (or Vc/a0) one: 1.2^3.5 = 1.892929.
const double kSonicPressureRatio = std::pow(1.0 + kHalfGammaMinusOne, kGammaOverGammaMinusOne);

[[noreturn]] void ThrowDomain(const char* function,
                              const char* name,
                              double value,
                              const char* rule) {
  std::ostringstream message;
  message << function << ": " << name << " = " << value << " " << rule;
  throw std::domain_error(message.str());
}

// sqrt(5·[(1 + ratio)^(2/7) − 1]) = Vc/a0 or M; the inverse of (1 + 0.2·x²)^3.5 − 1.
double SpeedRatioOfPressureRatio(double ratio) {
  return std::sqrt((std::pow(1.0 + ratio, kGammaMinusOneOverGamma) - 1.0) / kHalfGammaMinusOne);
}

}  // namespace

double SeaLevelSpeedOfSoundMps() {
  static const double a0_mps = SpeedOfSoundMps(kIsaSeaLevelTemperature_k);
  return a0_mps;
}

double ImpactPressurePa(double cas_mps) {
  const double a0_mps = SeaLevelSpeedOfSoundMps();
  if (!(cas_mps >= 0.0 && cas_mps <= a0_mps)) {
    std::ostringstream rule;
    rule << "m/s is outside the subsonic range [0, " << a0_mps << "] m/s";
    ThrowDomain("ImpactPressurePa", "cas_mps", cas_mps, rule.str().c_str());
  }
  const double v_ratio = cas_mps / a0_mps;
  return kIsaSeaLevelPressure_pa *
         (std::pow(1.0 + kHalfGammaMinusOne * v_ratio * v_ratio, kGammaOverGammaMinusOne) - 1.0);
}

double CalibratedAirspeedMps(double qc_pa) {
  const double max_qc_pa = kIsaSeaLevelPressure_pa * (kSonicPressureRatio - 1.0);
  if (!(qc_pa >= 0.0 && qc_pa <= max_qc_pa)) {
    std::ostringstream rule;
    rule << "Pa is outside the subsonic range [0, " << max_qc_pa << "] Pa";
    ThrowDomain("CalibratedAirspeedMps", "qc_pa", qc_pa, rule.str().c_str());
  }
  return SeaLevelSpeedOfSoundMps() * SpeedRatioOfPressureRatio(qc_pa / kIsaSeaLevelPressure_pa);
}

double ImpactPressurePaFromKt(double cas_kt) { return ImpactPressurePa(common::KtToMps(cas_kt)); }

double CalibratedAirspeedKt(double qc_pa) { return common::MpsToKt(CalibratedAirspeedMps(qc_pa)); }

double MachNumber(double qc_pa, double ps_pa) {
  if (!(ps_pa > 0.0 && std::isfinite(ps_pa))) {
    ThrowDomain("MachNumber", "ps_pa", ps_pa, "Pa is not a positive finite static pressure");
  }
  const double max_qc_pa = ps_pa * (kSonicPressureRatio - 1.0);
  if (!(qc_pa >= 0.0 && qc_pa <= max_qc_pa)) {
    std::ostringstream rule;
    rule << "Pa is outside the subsonic range [0, " << max_qc_pa << "] Pa at ps_pa = " << ps_pa;
    ThrowDomain("MachNumber", "qc_pa", qc_pa, rule.str().c_str());
  }
  return SpeedRatioOfPressureRatio(qc_pa / ps_pa);
}

double TrueAirspeedMps(double mach, double static_temp_k) {
  if (!(mach >= 0.0 && mach <= 1.0)) {
    ThrowDomain("TrueAirspeedMps", "mach", mach, "is outside the subsonic range [0, 1]");
  }
  return mach * SpeedOfSoundMps(static_temp_k);
}

}  // namespace adahrs::common
