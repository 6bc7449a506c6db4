// Improved ADS strategies that the firmware runs: surfaces fitted for the specification rather
// than for the mean square, minimising the worst error in units of the tolerance at the calibration
// points, max_i |r_i| / tol_i, by Lawson's iteratively reweighted least squares from w_i =
// 1/tol_i^2 (tolerance_minimax), plus pressure surfaces with a law, held-out temperature order and
// hysteresis regressors (pressure_minimax, hysteresis_compensated). Tolerances are
// calib/acceptance/ads_tolerance.h's. Output as the reference's (constants, standard errors,
// diagnostics) plus the worst ratio at the points of the first and the kept fit.
// Units: altitude in ft, airspeed in kt, pressures in Pa, codes in counts.
// Derivations, citations, measured figures: docs/calibration-strategies.md ("Improved strategies:
// `tolerance_minimax`, `pressure_minimax`, `hysteresis_compensated`").
// Left out: hysteresis in the static strategies (a single-valued surface returns one branch);
// tolerance_minimax keeps the 10-term cubic's temperature order, which cannot follow the bridge
// over -40...+85 degC.
#pragma once

#include <string>
#include <vector>

#include "calib/ads_calibration/bridge_history.h"
#include "calib/ads_calibration/reference_ads_strategy.h"

namespace adahrs::calib {

inline constexpr const char* kToleranceAdsStrategyName = "tolerance_minimax";
inline constexpr const char* kPressureAdsStrategyName = "pressure_minimax";
inline constexpr const char* kHysteresisAdsStrategyName = "hysteresis_compensated";
inline constexpr int kLawsonIterations = 40;

/// Fits the tolerance-minimax strategy; `context` leads every message; throws
/// DegenerateDesignError as the reference strategy does.
AdsFitResult FitToleranceAdsStrategy(const std::string& context,
                                     const std::vector<AdsCalibrationPoint>& points);

/// The same minimax, for the firmware's pressure laws (air_data_law.h): surfaces of the test set's
/// static and impact pressure (Pa), each point's tolerance carried into Pa by the law's local
/// slope (tol_Pa = tol_ft |dp/dh|, tol_kt dqc/dCAS), and the ISA and CAS laws after them in the
/// firmware. Pressure is the variable the bridge is nearly linear in; altitude and airspeed are
/// not (logarithmic and square-root laws), which is what the direct cubic wastes its terms on.
/// The states are those of each bridge's spans as estimated from the points
/// (EstimateHysteresisSpans, diagnostics "hysteresis_spans").
/// Each surface is the full tensor of degree 3 in the pressure code and q in the temperature code,
/// q in 3..5 chosen by held-out chamber temperatures (each interior temperature left out in turn,
/// the worst held-out |error| / tolerance compared; diagnostics list every candidate's score).
/// The bridge's ratiometric span tempco makes its temperature behaviour high order in the
/// bridge-voltage code; q = 5 needs at least 7 chamber temperatures to be a candidate.
AdsFitResult FitPressureAdsStrategy(const std::string& context,
                                    const std::vector<AdsCalibrationPoint>& points);

/// pressure_minimax's surfaces for a unit that compensates its hysteresis itself
/// (target/ads_constants.h HysteresisTermQ) and linearises its bridge codes (target/
/// bridge_linearisation.h; the linearisation fitted per bridge by bridge_linearisation_fit.h, and
/// every surface, order choice and die-temperature cubic then in the linearised code): the
/// temperature order chosen as there but with the states as recorded; one least-squares fit
/// weighted 1/tol^2 with the states and the states times (T - 25 degC) as regressors gives the
/// surface (the loop's centre) and the gains (the half loops, Pa per unit state, and their change
/// per degC). (A minimax surface of the branch-free z was measured and not kept: 1,582 failing
/// altitude grid points over 20 units against 1,454.) Exported with each operator's span
/// (pressure in Pa, the surface's z being Pa; temperature in degC) and the die temperature as a
/// cubic of the linearised code (least squares of the chamber temperatures over the points; needs
/// 4 temperatures). Diagnostics as pressure_minimax's plus that cubic's rms residual and the
/// linearisation (curvature with its standard error, slope, the quadratic's residual in degC).
/// The operators' spans are estimated from the points (EstimateHysteresisSpans, from `start`)
/// unless `span_choice` is kAssumed, when `start` is taken as the part's (the tests' "assumed
/// spans" column); diagnostics carry the estimate per surface ("hysteresis_spans").
/// Left out: the unit's state at power-on (virgin; the bridge keeps its hysteresis state across
/// power cycles, the firmware does not).
enum class SpanChoice { kEstimated, kAssumed };
AdsFitResult FitHysteresisAdsStrategy(const std::string& context,
                                      const std::vector<AdsCalibrationPoint>& points,
                                      const HysteresisSpans& start = HysteresisSpans::Nominal(),
                                      SpanChoice span_choice = SpanChoice::kEstimated);

/// Each bridge's pressure and thermal spans that let its centre fit explain the points best
/// (hysteresis_span_fit.h), searched around `start`; with `diagnostics`, sets each surface's
/// `hysteresis_spans` (spans, standard errors, the weighted cost at `start` and at the estimate).
HysteresisSpans EstimateHysteresisSpans(const std::string& context,
                                        const std::vector<AdsCalibrationPoint>& points,
                                        const HysteresisSpans& start,
                                        AdsFitDiagnostics* diagnostics);

/// The ADS strategy called `name` ("reference", "tolerance_minimax", "pressure_minimax" or
/// "hysteresis_compensated");
/// throws std::invalid_argument naming the known strategies for any other name.
AdsFitResult FitAdsStrategy(const std::string& name,
                            const std::string& context,
                            const std::vector<AdsCalibrationPoint>& points);

}  // namespace adahrs::calib
