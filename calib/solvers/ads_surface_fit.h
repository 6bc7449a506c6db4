// Air-data surfaces (thesis sections 2.9.1 and 4.3.1, Table 25): a bivariate polynomial of the
// pressure code x (static or pitot) and the same bridge's voltage code y, fitted to the reference
// values of an air data test set at several chamber temperatures. FitReferenceSurface is the
// reference's 10-term cubic; FitSurface takes any basis firmware_model::SurfaceFit holds (x up to
// 3, y up to 5), optionally weighted and with HistoryTerms separating the hysteresis branch from
// the surface. Fitted in the normalised code box and re-expanded in raw codes with the box.
// Units: codes in counts; z in the reference's unit (ft, kt, Pa); standard errors from the
// residual variance (mostly model error).
// Derivation, weighting and refusals: docs/calibration-solvers.md ("Models", ADS surface).
// Left out: hysteresis without HistoryTerms (a single-valued surface cannot hold it).
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
