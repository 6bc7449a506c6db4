// Reference air-data surface (thesis sections 2.9.1 and 4.3.1, Table 25): the 10-term bivariate
// cubic
//   z = a + b x + c y + d x^2 + e y^2 + f x y + g x^3 + h y^3 + i x y^2 + j x^2 y
// with x the pressure code (static for altitude in ft, pitot for airspeed in kt) and y the same
// bridge's temperature code (its bridge voltage), fitted to the reference values of an air data
// test set at several chamber temperatures. Fitted in normalised inputs (the code box mapped onto
// [-1, 1]^2) and re-expanded in raw codes for firmware_model::SurfaceFit, with the box, which the
// exporter normalises to again (polynomial_basis.h).
// Weighting: equal, as the reference's TableCurve 3-D fit (the reference instead places more
// points where the tolerance is tight), unless the samples carry weights (the tolerance-weighted
// strategy, tolerance_ads_strategy.h): then sum w_i r_i^2 is minimised, w_i read as relative
// inverse variances. Standard errors from the residual variance; the residuals
// here are mostly model error (the cubic cannot follow the bridge's temperature behaviour), so they
// describe the fit's spread, not noise.
// Refused: fewer than 4 distinct chamber temperatures (the y, y^2, y^3 terms need four; the
// bridge-voltage code alone cannot show it, since pressure and noise move it slightly even at one
// temperature and normalisation would stretch that into a spurious regressor), fewer than 4
// distinct reference values (likewise for x, x^2, x^3: the pressure code moves with temperature), fewer than 11
// points, or a degenerate design (the message names the near-null combination of terms).
// Not modelled: pressure or thermal hysteresis (a single-valued surface cannot).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "calib/solvers/linear_least_squares.h"
#include "calib/solvers/polynomial_fit.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct SurfaceSample {
  double x_code = 0.0;  ///< pressure code
  double y_code = 0.0;  ///< bridge-voltage (temperature) code
  double z = 0.0;       ///< reference value: altitude ft or airspeed kt
  double chamber_c = 0.0;  ///< the step's chamber temperature (reference instrument), degC
  double weight = 1.0;     ///< > 0; all 1 in the reference strategy
};

struct SurfaceEstimate {
  firmware_model::SurfaceFit surface;     ///< raw-code coefficients a..j and the code box
  std::array<double, 10> coeff_se{};      ///< standard errors of the raw coefficients
  PolynomialFit fit;                      ///< normalised fit, covariance and diagnostics
  double residual_rms = 0.0;              ///< z units
  double max_abs_residual = 0.0;          ///< z units
};

/// Fits the reference surface; `context` ("altitude surface") leads every message; throws
/// DegenerateDesignError with the reason.
SurfaceEstimate FitReferenceSurface(const std::string& context,
                                    const std::vector<SurfaceSample>& samples,
                                    const LeastSquaresOptions& options = {});

}  // namespace adahrs::calib
