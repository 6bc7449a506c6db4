// Acceptance judging: a calibrated unit's own compensated output, recorded during an acceptance
// sequence, against the reference the instruments report (never simulator truth) and the
// specification (specification.h). Rows of a step are those with the step's TAG and index,
// outside meta.json's rejected intervals. One point per acquisition and quantity: accel and
// cross_axis steps at rest (f_B = up axis * local gravity, mg), gyro steps per commanded rate
// (w_B = up axis * table_rate_dps, deg/s), thermal_profile steps per 5 degC chamber bin, ADS log
// steps in ft and kt (ISA pressure altitude, calibrated airspeed). Statistic: mean of (measured -
// reference) per packet with its standard error; pass when |mean error| <= tolerance, MARGINAL
// when it passes inside the specification's marginal band; with a rest record, rate points carry
// their physical limit (rest_stability.h). Thermal acceptance: with the specification's
// thermal_stability, a thermal_profile step also gives per body axis the standard deviation of the
// error's 1 s means over the whole step (thermal_accel_std_x..z in mg, thermal_rate_std_x..z in
// deg/s), which passes when it is at most the limit.
// Frames: body axes B of the IMU; units in each point's `unit`.
// Derivations, mode by mode quantities, Earth rate, refusals: docs/acceptance.md ("What is
// compared with what", "Rate points", "Refused input").
// Left out: heading and attitude, accelerations during rotation, rates in accel steps, Mach/TAS.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "calib/acceptance/rest_stability.h"
#include "calib/acceptance/specification.h"

namespace adahrs::calib {

class AcceptanceInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A point's mean chamber temperature may lie this far outside the rating (-40...+85 degC) and
/// still be judged: the shipped acceptance sequences soak at the rating's ends with a 0.5 degC
/// band.
inline constexpr double kRatingMarginC = 0.5;
/// Width of the chamber temperature bins a thermal_profile step is judged in.
inline constexpr double kThermalBinWidthC = 5.0;
/// A thermal bin with fewer packets is not judged (the chamber only touched it).
inline constexpr size_t kMinThermalBinPackets = 10;
/// The thermal acceptance's standard deviation is over means of this length: the ADXRS150's white
/// noise (about 0.35 deg/s per 10 ms packet) would otherwise be most of it.
inline constexpr double kThermalStabilityMean_s = 1.0;

/// Bias wander is counted over this time between calibration and acceptance unless told otherwise:
/// a production line accepts within a day of calibrating. The limit grows as ln(T), so a factor
/// of 10 in T moves it by about 15 %.
inline constexpr double kDefaultSinceCalibration_h = 24.0;
/// The longest time since calibration accepted (about 11 years).
inline constexpr double kMaxSinceCalibration_h = 1e5;

struct AcceptanceOptions {
  double since_calibration_h = kDefaultSinceCalibration_h;
};

/// The verdict of a point against the specification and, for rate points, its physical limit.
enum class PointVerdict {
  kWithinSpecification,
  kWithinPhysicalLimit,
  kOutsideBoth,
  kOutsideSpecification
};

/// PASS, MARGINAL (passes within the marginal band below the tolerance) or FAIL.
enum class Outcome { kPass, kMarginal, kFail };

/// "PASS", "MARGINAL", "FAIL".
const char* OutcomeText(Outcome outcome);

/// "within specification", "outside specification, within the physical limit", "outside
/// specification and the physical limit", "outside specification" (no limit known): the wording
/// the acceptance table, acceptance.json, the report and the demo summary share.
const char* PointVerdictText(PointVerdict verdict);

/// One quantity judged at one acquisition.
struct AcceptancePoint {
  int step = 0;          ///< step index in the run's sequence
  std::string kind;      ///< the step's kind: accel, gyro, cross_axis, thermal_profile, log
  std::string quantity;  ///< accel_x..z, rate_x..z, altitude, airspeed
  std::string unit;      ///< of measured, reference, error, std_error, tolerance
  int orientation = 0;   ///< IMU: fixture orientation code; 0 for ADS
  std::optional<double> rate_dps;  ///< IMU: commanded table rate about the up axis
  std::optional<double> alt_ft;    ///< ADS: aimed pressure altitude
  std::optional<double> cas_kt;    ///< ADS: aimed calibrated airspeed
  double chamber_c = 0.0;          ///< mean chamber temperature as the controller reported it
  /// Thermal stability points: the lowest and highest chamber temperature of the step.
  std::optional<double> chamber_min_c{}, chamber_max_c{};
  int samples = 0;
  double measured = 0.0;    ///< mean of the unit's output
  double reference = 0.0;   ///< mean of the instruments' reference
  double error = 0.0;       ///< mean of (measured - reference) per packet
  double std_error = 0.0;   ///< standard error of `error`, packets taken as independent
  double duration_s = 0.0;  ///< IMU: packets x frame period; ADS: first to last arrival
  double noise = 0.0;       ///< 1-sigma noise of `error`: std_error, or the rest record's if larger
  double tolerance = 0.0;   ///< +- at the input, from the specification
  double marginal_band = 0.0;            ///< fraction of the tolerance below it that is MARGINAL
  std::optional<double> physical_limit;  ///< rate points with a rest record (rest_stability.h)
  bool pass = false;
  bool beyond_noise = false;  ///< | |error| - tolerance | > 2 noise

  PointVerdict verdict() const;
  /// FAIL unless pass; MARGINAL when |error| > (1 - marginal_band) x tolerance; else PASS.
  Outcome outcome() const;
  double margin() const;  ///< tolerance - |error| (negative when failing)
  /// "orientation 11, 62.5 deg/s, 25.0 degC" / "5000 ft, 60 kt, -20.0 degC" / "orientation 31,
  /// 25.0...85.0 degC" (a thermal stability point): where it was judged.
  std::string Condition() const;
};

/// The smallest margin of one family of quantities (acceleration, body rate, altitude, airspeed).
struct WorstMargin {
  std::string quantity;  ///< "acceleration", "body_rate", "altitude", "airspeed"
  std::string unit;
  double margin = 0.0;  ///< tolerance - |error| at the worst point
  int step = 0;
  std::string point;  ///< the worst point's quantity and condition
};

struct UnitAcceptance {
  std::string serial;
  std::string kind;  ///< "imu" | "ads"
  int mode = 0;      ///< the compensated mode its rows were recorded in
  std::vector<AcceptancePoint> points;
  std::optional<RestStability> rest;  ///< IMU: the rest record the noise and limits come from

  bool pass() const;
  int failed() const;
  int marginal() const;  ///< points that pass inside the marginal band
  /// FAIL when any point fails, MARGINAL when none fails and any is marginal, else PASS.
  Outcome outcome() const;
  /// Points of `family` ("acceleration", "body_rate", "altitude", "airspeed") with `verdict`.
  int Count(const std::string& family, PointVerdict verdict) const;
  std::vector<WorstMargin> WorstMargins() const;
};

struct AcceptanceRun {
  std::string run_dir;
  std::string run_id;
  std::string recording_sha256;
  std::string sequence_name;
  double since_calibration_h = kDefaultSinceCalibration_h;  ///< of the physical limits
  double local_gravity_mps2 = 0.0;                          ///< 0 for an ADS run
  std::vector<UnitAcceptance> units;                        ///< in meta.json's order

  bool pass() const;
};

/// Judges every unit of the run in `run_dir` against `spec`; throws AcceptanceInputError or
/// hil::RecordingError with the reason.
AcceptanceRun JudgeAcceptance(const std::filesystem::path& run_dir,
                              const Specification& spec,
                              const AcceptanceOptions& options = {});

/// "acceleration" for accel_x..z, "body_rate" for rate_x..z, "thermal_acceleration_std" for
/// thermal_accel_std_x..z, "thermal_body_rate_std" for thermal_rate_std_x..z, else the quantity.
std::string QuantityFamily(const std::string& quantity);

}  // namespace adahrs::calib
