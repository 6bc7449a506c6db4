// The hysteresis states of the ADS's two pressure bridges at each calibration point, from the
// history the reference instruments imposed (shared/physics.md section 6 rows 4 and 7): a bridge's
// output carries S (h_P/2) s_P + S (h_T/2) s_T, s_P and s_T in [-1, 1] the Preisach states of
// pressure and die temperature (-1 after a rise, +1 after a fall). The states are those of the
// operator the unit runs (unit_hysteresis_operator.h) driven in step order by the test set's
// static (static bridge) and impact (pitot bridge) pressure and the chamber temperature, from the
// virgin state; with them as regressors a surface returns the loop's centre, not one branch.
// Spans per bridge; Nominal() is the class's estimate (20 % of full scale, 20 degC), which
// hysteresis_span_fit.h refines from the recording.
// Units: pressures in Pa, temperatures in degC, states dimensionless.
// Why the points alone carry the history, the initial state: docs/calibration-strategies.md
// (`pressure_minimax` item 3, "The states at the points").
// Left out: die temperature lagging the chamber during a step's dwell (points are taken after the
// soak); a real unit's history before the run (a full excursion of the sequence erases it).
#pragma once

#include <vector>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct HysteresisSpans {
  double static_pressure_pa = 0.0;  ///< travel after a reversal to the full pressure state
  double impact_pressure_pa = 0.0;
  double static_temperature_c = 0.0;  ///< likewise for each bridge's die temperature
  double pitot_temperature_c = 0.0;

  /// The model-1230 class's spans as estimated (bridge_history.cc: 20 % of 15 psi, 20 degC, E).
  static HysteresisSpans Nominal();
  /// The spans of a constants set's hysteresis operators: the static bridge's from the altitude
  /// surface, the pitot's from the airspeed surface; Nominal()'s where a surface has none (a term
  /// without a span has no gain, so its state adds nothing).
  static HysteresisSpans Of(const firmware_model::AdsCalibrationConstants& constants);
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
