// Subsonic air-data relations used by the air data test set and the ADS unit (shared/protocols.md
// §5, shared/physics.md §4.1, both ISA, status V/D): calibrated airspeed ↔ impact pressure
// qc = pt − ps (St Venant / Bernoulli compressible flow referred to sea-level ISA), Mach number
// from qc and ps, and true airspeed from Mach and static air temperature.
//
//   qc = p0·[(1 + 0.2·(Vc/a0)²)^3.5 − 1],     Vc = a0·sqrt(5·[(qc/p0 + 1)^(2/7) − 1])
//   M  = sqrt(5·[(qc/ps + 1)^(2/7) − 1]),      TAS = M·sqrt(γ·R·T)
//
// with a0 = sqrt(γ·R·T0) = 340.294 m/s = 661.479 kt. The exponents 3.5 = γ/(γ−1) and
// 2/7 = (γ−1)/γ and the factor 0.2 = (γ−1)/2 follow from γ = 1.4.
//
// Not modelled: the supersonic (Rayleigh pitot) branch; these functions throw std::domain_error
// naming the value for Vc > a0, M > 1 or a negative airspeed/impact pressure. Static-source and
// pitot position errors, and total-temperature recovery, belong to the aircraft, not here.
#pragma once

namespace adahrs::common {

/// Sea-level ISA speed of sound a0 = sqrt(γ·R·T0), m/s (340.294 m/s, physics.md §4.1).
double SeaLevelSpeedOfSoundMps();
/// Impact pressure (Pa) for calibrated airspeed `cas_mps` in [0, a0].
double ImpactPressurePa(double cas_mps);
/// Calibrated airspeed (m/s) for impact pressure `qc_pa` in [0, qc(a0)].
double CalibratedAirspeedMps(double qc_pa);
/// Impact pressure (Pa) for calibrated airspeed `cas_kt` in knots.
double ImpactPressurePaFromKt(double cas_kt);
/// Calibrated airspeed in knots for impact pressure `qc_pa`.
double CalibratedAirspeedKt(double qc_pa);
/// Mach number from impact pressure `qc_pa` ≥ 0 and static pressure `ps_pa` > 0 (subsonic).
double MachNumber(double qc_pa, double ps_pa);
/// True airspeed (m/s) at Mach `mach` in [0, 1] and static air temperature `static_temp_k`.
double TrueAirspeedMps(double mach, double static_temp_k);

}  // namespace adahrs::common
