// The hysteresis states of the ADS's two pressure bridges at each calibration point, from the
// history the reference instruments imposed (shared/physics.md section 6 rows 4 and 7): a
// bridge's output carries S (h_P/2) s_P + S (h_T/2) s_T, where
// s_P and s_T in [-1, 1] are Preisach states of pressure and of die temperature (-1 after a
// rise, +1 after a fall, set by the extremes that are not wiped out). A single-valued surface
// fitted to points recorded on one branch returns that branch, not the loop's centre; with the
// states as regressors (tolerance_ads_strategy.h) it returns the centre.
//
// The states are those of the Preisach operator the unit runs (unit_hysteresis_operator.h) driven
// by the reference history in step order: the test set's static pressure (static bridge) and impact
// pressure (pitot bridge), and the chamber temperature (both dies; after a soak the die sits at
// the chamber's temperature). Between calibration points the test set and the chamber move
// monotonically from one aim to the next (the sequence's steps), so every reversal that matters
// happens at a point and the points alone carry the history: the test set's noise and the
// chamber's overshoot make minor loops that the operator's return-point memory forgets once the
// input passes back, which it does on the way to the next point. Before the first point the unit
// is taken to be at rest in the room, demagnetised (the operator's virgin state): 25 degC,
// standard sea-level static pressure, no impact pressure; the sequence's first full excursions
// wipe that out.
// Spans: each bridge has its own (a part's spans are not given by any datasheet). Nominal() holds
// the class's estimate (physics.md section 6: E), 20 % of full scale and 20 degC, which the
// hysteresis-compensated strategy starts from and then estimates from the recording
// (hysteresis_span_fit.h).
// Left out: die temperature lagging the chamber during a step's dwell (the points are taken after
// the soak); a real unit's history before the run (a full excursion of the sequence erases it).
#pragma once

#include <vector>

#include "calib/ads_calibration/ads_calibration_points.h"

namespace adahrs::calib {

struct HysteresisSpans {
  double static_pressure_pa = 0.0;  ///< travel after a reversal to the full pressure state
  double impact_pressure_pa = 0.0;
  double static_temperature_c = 0.0;  ///< likewise for each bridge's die temperature
  double pitot_temperature_c = 0.0;

  /// The model-1230 class's spans as estimated (bridge_history.cc: 20 % of 15 psi, 20 degC, E).
  static HysteresisSpans Nominal();
};

struct BridgeStates {
  double s_pressure = 0.0;  ///< in [-1, 1]
  double s_thermal = 0.0;   ///< in [-1, 1]
};

struct PointHistory {
  BridgeStates static_bridge;
  BridgeStates pitot_bridge;
};

/// The states at each of `points` (in step order, as SelectAdsCalibrationPoints returns them).
std::vector<PointHistory> BridgeHistoryOf(
    const std::vector<AdsCalibrationPoint>& points,
    const HysteresisSpans& spans = HysteresisSpans::Nominal());

/// The band of states that the operating envelope's histories can leave at input `x`: fresh (0),
/// after a major loop low -> high -> x, and after high -> low -> x (the histories
/// proving/evaluation/ads_evaluation.h judges a unit under). A surface that reads the middle of
/// that band at every point has the smallest worst error over them, and no surface does better
/// than the band's half-width times the half loop; near the envelope's ends only one branch is
/// reachable (nothing arrives at -40 degC but by cooling), so the middle there is not the loop's
/// centre.
struct StateBand {
  double mid = 0.0;
  double half_width = 0.0;
};
StateBand EnvelopeStateBand(double x, double low, double high, double span);

struct BridgeBands {
  StateBand pressure;
  StateBand thermal;
};
struct PointBands {
  BridgeBands static_bridge;
  BridgeBands pitot_bridge;
};

/// The bands of each bridge at the reference pressures and chamber temperature of `point`, over
/// the specification's envelope (-1,000...50,000 ft, 30...450 kt, -40...+85 degC).
PointBands EnvelopeBands(const AdsCalibrationPoint& point,
                         const HysteresisSpans& spans = HysteresisSpans::Nominal());

}  // namespace adahrs::calib
