// Truth evaluation of IMU constants (simulated units only; docs/evaluation-format.md): the
// constants are exported to the firmware's fixed-point blocks (constants_exporter.h) and run
// through the target compensator (firmware_model/target/imu_compensator.h, fully calibrated mode)
// on a dense grid of the envelope, with the unit's TRUE model (truth.json -> ImuUnitParams), and
// the outputs are compared with the true inputs.
//
// Grid: chamber temperatures -40...+85 degC in 12.5 degC steps; at each, the six orientations at
// rest (A against local gravity along the up axis) and rates -150...+150 deg/s by 50 about each
// axis (G against the rate about the up axis). Each point averages `frames` frames after
// `settle_frames`. The noise switches are off (accelerometer white noise, gyro white noise, bias
// instability, rate random walk) and the die lag is off (a steady-state grid: the die sits at the
// air temperature plus its self-heating); every other effect of the truth model stays as drawn,
// including T2 jitter, which dithers the capture quantisation so that the mean is the steady-state
// output, not a quantisation artefact.
// Verdict per quantity (acceleration, body rate), worded as acceptance words its points
// (acceptance_judge.h); the physical limit here is the calibration design's, 3 sigma_p:
//   "within specification"        every point's error is within the specification;
//   "outside specification, within 1.5x the physical limit"
//                                 every point outside it is within 1.5 x 3 sigma_p, sigma_p the
//                                 standard deviation of that output implied by the Cramer-Rao
//                                 covariance of the constants (diagnostics.crb_covariance of the
//                                 joint strategy) through the compensator's Jacobian,
//                                 sigma_p^2 = j' CRB j (3 sigma: a per-point 99.7 % bound);
//   "outside specification, within 1.5x the firmware floor plus the physical limit"
//                                 the worst error is within 1.5 x (the
//                                 worst error of the best constants the firmware's structure can
//                                 hold — the firmware floor, below — plus the largest 3 sigma_p);
//                                 the 1.5 is the required margin, applied to the floor because the
//                                 floor is the equal-weight projection over the grid, not the
//                                 minimax constants, nor those the recording's design leads to;
//   "outside specification and the physical limit"   none of these;
//   "outside specification"       no CRB covariance (the reference strategy): no limit to judge.
// The firmware floor: the true unit projected onto the firmware's model (the joint model fitted
// with the firmware's thermal order, 3, to the noise-free grid, equal weights; with the format-3
// terms, scale factors of order 3, when the constants have them, but not the die-lag nuisance
// terms: the grid is steady state) and run through the same compensator; its worst error is what
// these constants leave at best in the least-squares sense (e.g. a scale factor that changes with
// temperature, which format 2 has no term for; docs/calibration-strategies.md "The firmware floor,
// effect by effect"). Not the minimax: a fit's worst error can fall somewhat below it.
// Without a CRB covariance (the reference strategy) only the specification is judged. Constants
// the exporter refuses are refused here (std::invalid_argument with the exporter's reason); a
// projection it refuses leaves the floor unknown (NaN).
// Parameters: the projection above gives a "true" value per constant; each constant's error is
// reported against its standard error and its CRB standard error, with the ratios.
// Not evaluated: dynamics (lag, filter), vibration, supply variation, attitude.
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "calib/acceptance/specification.h"
#include "calib/constants/constants_file.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {

struct ImuEvaluationOptions {
  double g_local_mps2 = 9.80665;  ///< the station gravity the constants were fitted with
  int settle_frames = 20;
  int frames = 100;
  uint64_t seed = 1;
};

struct ImuEvaluation {
  double worst_accel_mg = 0.0;
  double worst_rate_dps = 0.0;
  std::string accel_verdict;
  std::string rate_verdict;
  nlohmann::json report;  ///< evaluation.json
};

/// The constants are valid but the firmware exporter cannot hold them: a result of the strategy
/// (reported as a verdict by callers that evaluate many units), not malformed input.
class ConstantsNotExportable : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Evaluates `constants` (kind imu) against `truth`; throws ConstantsNotExportable when the
/// exporter refuses them, std::invalid_argument when they are not an IMU's or malformed.
ImuEvaluation EvaluateImu(const calib::ConstantsFile& constants,
                          const sensor_sim::ImuUnitParams& truth,
                          const calib::Specification& spec,
                          const ImuEvaluationOptions& options = {});

/// The firmware floor alone (no constants to judge): the worst |error| over the grid of the true
/// unit projected onto the format-2 model, or the format-3 model when `format3`, as EvaluateImu
/// reports it (worst_firmware_floor_mg, worst_firmware_floor_dps); NaN when the exporter cannot
/// hold the projection.
struct ImuFirmwareFloor {
  double worst_accel_mg = 0.0;
  double worst_rate_dps = 0.0;
};
ImuFirmwareFloor EvaluateImuFirmwareFloor(const sensor_sim::ImuUnitParams& truth,
                                          bool format3,
                                          const ImuEvaluationOptions& options = {});

}  // namespace adahrs::proving
