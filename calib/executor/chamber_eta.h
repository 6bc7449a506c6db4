// The remaining time of a chamber wait (reach target +- band, then stay inside for the soak) as
// the chamber itself shows it, for the progress ETA. The plan's estimate comes from the station's
// declared ramp rates (execution_plan.h); a real chamber heats and cools at what its heater and
// compressor allow, then settles onto the set point as its control loop closes. Two laws of the
// distance e = |target - process value| are fitted to the last kChamberRateWindowS: a ramp at
// the chamber's capacity (e falls at a constant rate: a line through e) and the closed loop's
// settling (e falls exponentially: a line through ln e), both by least squares; the settling law
// is extrapolated to the band's edge when its residuals in e are under half the ramp's, the ramp
// otherwise, plus the whole soak; inside the band, what is left of the soak.
// Units: degC, pipeline clock seconds.
// Left out: during a ramp, the settling still to come after it (it shows only once the approach
// slows: the ETA is then short by it); a chamber moving away from its target (no estimate: the
// plan's stands).
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

namespace adahrs::calib {

/// The trailing window the approach rate is measured over.
inline constexpr double kChamberRateWindowS = 120.0;
/// Less evidence than this (time or approach) gives no estimate.
inline constexpr double kChamberMinWindowS = 30.0;
inline constexpr double kChamberMinApproachC = 0.2;
inline constexpr size_t kChamberMinReadings = 8;
/// The settling law is taken only when its residuals are below this fraction of the ramp's.
inline constexpr double kChamberSettleRssRatio = 0.5;

class ChamberEta {
 public:
  ChamberEta(double target_c, double band_c, double soak_s)
      : target_c_(target_c), band_c_(band_c), soak_s_(soak_s) {}

  /// One reading of the process value at clock time `now_s`; `inside_since_s` is when it entered
  /// the band (< 0 outside).
  void Observe(double now_s, double pv_c, double inside_since_s);

  /// Seconds left by the measured approach; nullopt while the evidence is thin.
  std::optional<double> RemainingS() const;

 private:
  double target_c_, band_c_, soak_s_;
  std::deque<std::pair<double, double>> window_;  // (clock s, process value degC)
  double inside_since_s_ = -1.0;
};

}  // namespace adahrs::calib
