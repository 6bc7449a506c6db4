// How still a calibrated IMU's own output is at rest, read from an acceptance recording, and the
// error limit that noise and bias wander impose on an acceptance point. Rest record: the unit's
// longest run of consecutive compensated packets (mode 2 or 3, one frame apart by
// hil::FramesBetween) with the table at rest (kRestRate_dps), one orientation, the chamber within
// kRestBand_c, its last kRestRecordMax_s; per body axis the overlapping Allan deviation
// (calib/solvers/allan_terms.h). Limit of a point of duration tau_p judged T after calibration:
// 3 sqrt(sigma_point^2 + sigma_wander^2), sigma_point = max(s / sqrt(n), sigma_A(tau_p)),
// sigma_wander from the flicker floor and Barnes's B2 (NIST TN 1318). Acceptance reports it beside
// the specification; it never widens the specification.
// Units and frames: f_B in mg, w_B in deg/s, body axes; tau and T in seconds.
// The rest record, the formulas and their sources: docs/acceptance.md ("Rate points").
// Left out: rate random walk and rate ramp beyond the rest record, the calibration's own
// estimation error (the constants' CRB), temperature dependence of the noise.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/solvers/allan_terms.h"
#include "hil/recording/recording_format.h"

namespace adahrs::calib {

/// A packet belongs to the rest record when the table reports at most this rate.
inline constexpr double kRestRate_dps = 0.01;
/// A rest stretch ends where the chamber leaves this band around its first packet's temperature.
inline constexpr double kRestBand_c = 1.0;
/// The rest record is at most this long (its end is kept).
inline constexpr double kRestRecordMax_s = 1800.0;
/// A shorter rest record gives no curve: the limit is not reported.
inline constexpr double kRestRecordMin_s = 20.0;

/// A compensated packet's output along the body axes: mode 3 as the unit sends it (A converted to
/// g); mode 2 the mean of each axis's two accelerometer channels and the rates as sent.
struct ImuBodyOutput {
  std::array<double, 3> f_B_g{};
  std::array<double, 3> w_B_dps{};
};

/// The body output of a row in mode 2 or 3 (the caller checks the mode and that comp is present).
ImuBodyOutput BodyOutput(const hil::ImuRecordRow& row);

/// What acceptance keeps of one IMU row: the columns it judges and the body output, without the
/// serial, the raw channels and the compensated cells (about a quarter of the reader's row).
struct ImuOutputRow {
  double t_s = 0.0;
  double chamber_c = 0.0;
  double table_rate_dps = 0.0;
  ImuBodyOutput body;  ///< BodyOutput of the row; zero when the row carries no compensated values
  uint32_t seq = 0;
  int step = 0;
  int orientation = 0;
  uint8_t tag = 0;
  uint8_t mode = 0;
  bool has_comp = false;

  static ImuOutputRow Of(const hil::ImuRecordRow& row);
};

struct RestStability {
  double t_start_s = 0.0;  ///< first packet of the record, run time
  double record_s = 0.0;
  int orientation = 0;
  double chamber_c = 0.0;              ///< mean over the record
  std::array<AllanTerms, 3> accel_mg;  ///< x, y, z
  std::array<AllanTerms, 3> rate_dps;

  /// Allan deviation of one axis at `tau_s`, log-log interpolated; held at the curve's ends.
  static double SigmaAt(const AllanTerms& terms, double tau_s);
  /// The curve's minimum (the flicker floor, or an upper bound of it when the curve still falls).
  static double Floor(const AllanTerms& terms);
  /// The record without the curves, for acceptance.json.
  nlohmann::json ToJson() const;
};

/// Barnes's B2(r) for flicker noise: the two-sample variance of averages of length tau whose
/// starts are r * tau apart, over the Allan variance at tau. r < 1 is taken as 1.
double FlickerSeparationRatio(double r);

/// The rest record of one unit's rows (in recording order), or nothing when no stretch reaches
/// kRestRecordMin_s. `packet_period_s` is the units' frame period.
std::optional<RestStability> ReadRestStability(const std::vector<ImuOutputRow>& rows,
                                               double packet_period_s);

/// The 3-sigma limit of a point's mean error (see the header comment), in the terms' unit.
double PointLimit(const AllanTerms& terms,
                  double iid_std_error,
                  double point_s,
                  double since_calibration_s);

/// sigma_point of the header comment.
double PointSigma(const AllanTerms& terms, double iid_std_error, double point_s);

}  // namespace adahrs::calib
