// Truth evaluation of IMU constants (simulated units only): the constants are exported to the
// firmware's fixed-point blocks (constants_exporter.h) and run through the target compensator
// (firmware_model/target/imu_compensator.h, fully calibrated mode) on a dense steady-state grid of
// the envelope (temperatures, six orientations at rest, rates about each axis) with the unit's TRUE
// model (truth.json -> ImuUnitParams), noise and die lag off; outputs compared with the true
// inputs. Verdicts per quantity as acceptance words them, with the design's physical limit (3
// sigma of the CRB-implied output) and the firmware floor (the true unit projected onto the
// firmware's model); each constant's error against its standard error and CRB standard error.
// Frames and units: body axes B; acceleration in mg, body rate in deg/s, temperature in degC.
// Grid, verdicts, firmware floor, refusals: docs/evaluation-format.md; the floor effect by effect:
// docs/calibration-strategies.md ("The firmware floor, effect by effect").
// Left out: dynamics (lag, filter), vibration, supply variation, attitude.
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
