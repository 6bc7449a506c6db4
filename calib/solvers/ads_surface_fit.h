// Air-data surfaces (thesis sections 2.9.1 and 4.3.1, Table 25): a bivariate polynomial of the
// pressure code x (static for altitude or static pressure, pitot for airspeed or impact pressure)
// and the same bridge's temperature code y (its bridge voltage), fitted to the reference values of
// an air data test set at several chamber temperatures. The reference method's is the 10-term cubic
//   z = a + b x + c y + d x^2 + e y^2 + f x y + g x^3 + h y^3 + i x y^2 + j x^2 y
// (FitReferenceSurface); FitSurface takes any basis the firmware can hold (powers of x up to 3,
// of y up to 5: firmware_model::SurfaceFit). Fitted in normalised inputs (the code box mapped onto
// [-1, 1]^2) and re-expanded in raw codes for firmware_model::SurfaceFit, with the box, which the
// exporter normalises to again (polynomial_basis.h).
// Weighting: equal, as the reference's TableCurve 3-D fit (the reference instead places more
// points where the tolerance is tight), unless the samples carry weights (the tolerance-weighted
// strategies, tolerance_ads_strategy.h): then sum w_i r_i^2 is minimised, w_i read as relative
// inverse variances. Standard errors from the residual variance; the residuals here are mostly
// model error (a polynomial cannot follow the bridge's temperature behaviour exactly), so they
// describe the fit's spread, not noise.
// Refused: fewer distinct chamber temperatures than the highest power of y plus one (the bridge-
// voltage code alone cannot show it, since pressure and noise move it slightly even at one
// temperature and normalisation would stretch that into a spurious regressor), fewer distinct
// reference values than the highest power of x plus one (likewise: the pressure code moves with
// temperature), no more points than terms, or a degenerate design (the message names the
// near-null combination of terms).
// Hysteresis: a single-valued surface cannot hold it; with HistoryTerms the fit separates the
// points' branch (their hysteresis states, bridge_history.h) from the surface, which is then the
// loop's centre. The states must vary independently of x and y for that (a sequence that
// approaches temperatures and pressures from both sides); otherwise the design is refused as
// degenerate, naming the state.
#pragma once

#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "calib/solvers/linear_least_squares.h"
#include "calib/solvers/polynomial_basis.h"
#include "calib/solvers/polynomial_fit.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct SurfaceSample {
  double x_code = 0.0;      ///< pressure code
  double y_code = 0.0;      ///< bridge-voltage (temperature) code
  double z = 0.0;           ///< reference value: altitude ft, airspeed kt, or pressure Pa
  double chamber_c = 0.0;   ///< the step's chamber temperature (reference instrument), degC
  double weight = 1.0;      ///< > 0; all 1 in the reference strategy
  double s_pressure = 0.0;  ///< the bridge's pressure hysteresis state (bridge_history.h)
  double s_thermal = 0.0;   ///< its thermal hysteresis state
};

/// A chamber temperature as the key that tells calibration temperatures apart (0.1 degC).
inline long long ChamberTemperatureKeyDc(double chamber_c) {
  return std::llround(10.0 * chamber_c);
}

/// The samples' distinct chamber temperatures, as keys (ascending).
std::set<long long> ChamberTemperaturesDc(const std::vector<SurfaceSample>& samples);

/// Whether the fit carries the bridge's hysteresis states as regressors: z = surface(x, y)
/// + c_P s_P + c_T s_T. The surface is then the loop's centre (what a unit without history reads);
/// c_P and c_T are the half loops in z units. kWithTemperatureSlopes adds s_P dT and s_T dT,
/// dT = chamber_c - kHysteresisReferenceC: half loops that change with temperature (a bridge's
/// loop is a fixed fraction of its output at the reference temperature, pressure_bridge.h, so in
/// pressure it follows the span tempco, about +-15 % over -40...+85 degC).
enum class HistoryTerms { kNone, kPressureAndThermal, kWithTemperatureSlopes };

/// The temperature the half loops are given at.
inline constexpr double kHysteresisReferenceC = 25.0;

struct HysteresisEstimate {
  double pressure = 0.0;  ///< c_P, z units per unit state (at kHysteresisReferenceC)
  double pressure_se = 0.0;
  double thermal = 0.0;  ///< c_T
  double thermal_se = 0.0;
  double pressure_per_c = 0.0;  ///< d c_P / dT (kWithTemperatureSlopes; else 0)
  double pressure_per_c_se = 0.0;
  double thermal_per_c = 0.0;
  double thermal_per_c_se = 0.0;
};

struct SurfaceEstimate {
  firmware_model::SurfaceFit surface;              ///< raw-code coefficients and the code box
  firmware_model::SurfaceCoefficients coeff_se{};  ///< standard errors of the raw coefficients
                                                   ///< (NaN for a term outside the basis: held
                                                   ///< at zero, not fitted; null in the file)
  PolynomialFit fit;                               ///< normalised fit, covariance and diagnostics
  int terms = 0;                                   ///< the basis's size
  int y_degree = 0;                                ///< its highest power of y
  std::optional<HysteresisEstimate> history;       ///< with history terms
  double residual_rms = 0.0;                       ///< z units
  double max_abs_residual = 0.0;                   ///< z units
};

/// Fits `basis` (its x and y are the pressure and temperature codes; powers within the firmware's
/// 3 and 5); `context` ("altitude surface") leads every message; throws DegenerateDesignError with
/// the reason, std::invalid_argument for a basis the firmware cannot hold.
SurfaceEstimate FitSurface(const std::string& context,
                           const PolynomialBasis& basis,
                           const std::vector<SurfaceSample>& samples,
                           HistoryTerms history = HistoryTerms::kNone,
                           const LeastSquaresOptions& options = {});

/// FitSurface with the reference's 10-term cubic.
SurfaceEstimate FitReferenceSurface(const std::string& context,
                                    const std::vector<SurfaceSample>& samples,
                                    const LeastSquaresOptions& options = {});

}  // namespace adahrs::calib
