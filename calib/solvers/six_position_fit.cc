#include "calib/solvers/six_position_fit.h"

#include <fmt/format.h>

#include "calib/solvers/linear_least_squares.h"
#include "common/imu_layout.h"
#include "common/units.h"

namespace adahrs::calib {
namespace {

// Body axis (1 = x, 2 = y, 3 = z) each channel senses (docs/frames-and-units.md, IM3 channels).
constexpr std::array<int, 6> kAxisOfChannel = {3, 1, 2, 3, 1, 2};

const AccelOrientationMeans& FindStep(const std::vector<AccelOrientationMeans>& steps,
                                      int orientation,
                                      int channel) {
  const AccelOrientationMeans* found = nullptr;
  for (const AccelOrientationMeans& s : steps) {
    if (s.orientation != orientation) continue;
    if (found != nullptr) {
      throw DegenerateDesignError(
          fmt::format("six-position fit: orientation {} appears more than once", orientation));
    }
    found = &s;
  }
  if (found == nullptr) {
    throw DegenerateDesignError(
        fmt::format("six-position fit: design refused: orientation {} is missing (channel {} needs "
                    "{}1 and {}2)",
                    orientation,
                    common::kAccelChannelNames[channel],
                    orientation / 10,
                    orientation / 10));
  }
  return *found;
}

}  // namespace

std::array<AccelScaleEstimate, 6> FitSixPosition(const std::vector<AccelOrientationMeans>& steps,
                                                 double g_local_mps2) {
  const double g_local_g = common::Mps2ToG(g_local_mps2);
  std::array<AccelScaleEstimate, 6> out;
  for (int ch = 0; ch < 6; ++ch) {
    const int axis = kAxisOfChannel[ch];
    const AccelOrientationMeans& up = FindStep(steps, 10 * axis + 1, ch);
    const AccelOrientationMeans& down = FindStep(steps, 10 * axis + 2, ch);
    LinearLeastSquaresProblem problem;
    problem.context = fmt::format("six-position fit of {}", common::kAccelChannelNames[ch]);
    problem.term_names = {"O", "S"};
    problem.design.resize(2, 2);
    problem.design << 1.0, g_local_g, 1.0, -g_local_g;
    problem.observations.resize(2);
    problem.observations << up.t_duty[ch], down.t_duty[ch];
    problem.weights.resize(2);
    problem.weights << 1.0 / (up.t_duty_se[ch] * up.t_duty_se[ch]),
        1.0 / (down.t_duty_se[ch] * down.t_duty_se[ch]);
    problem.error_scale = ErrorScale::kKnownVariance;
    const LinearFit fit = SolveLinearLeastSquares(problem);

    AccelScaleEstimate& e = out[ch];
    e.fit.offset_duty = fit.coefficients[0];
    e.fit.scale_duty_per_g = fit.coefficients[1];
    e.offset_se_duty = fit.standard_errors[0];
    e.scale_se_duty_per_g = fit.standard_errors[1];
    e.inverse_scale_g_per_duty = 1.0 / e.fit.scale_duty_per_g;
    e.inverse_scale_se_g_per_duty =
        e.scale_se_duty_per_g / (e.fit.scale_duty_per_g * e.fit.scale_duty_per_g);
  }
  return out;
}

}  // namespace adahrs::calib
