// How still a calibrated IMU's own output is at rest, read from an acceptance recording, and the
// error limit that noise and bias wander impose on an acceptance point (docs/acceptance.md).
//
// Rest record: the unit's longest run of consecutive compensated packets (mode 2 or 3; one frame
// apart by hil::FramesBetween) with the table at rest
// (|reported rate| <= kRestRate_dps) in one orientation, the chamber within kRestBand_c of the
// stretch's first packet (a soak, not a ramp); its last kRestRecordMax_s only (the end of a soak
// is the stillest part). The samples are one frame period apart (the unit's clock, not the
// bursty arrival times). Per body axis the overlapping Allan deviation of f_B (mg) and w_B (deg/s)
// (calib/solvers/allan_terms.h).
//
// Limit of a point of duration tau_p judged T after calibration, per axis:
//   sigma_point  = max(s / sqrt(n), sigma_A(tau_p))   the point's mean against the unit's long-run
//                                                      mean (sigma_A read off the rest curve)
//   sigma_wander = sqrt(2 B2(T / tau_p)) sigma_floor  the bias then against the bias now, a flicker
//                  floor sigma_floor (the curve's minimum, 0.664 B in IEEE 952's terms) separated
//                  by T: B2 is Barnes's bias function for flicker noise (NIST TN 1318), 1 at r = 1,
//                  (2 ln r + 3) / (4 ln 2) for large r
//   limit        = 3 sqrt(sigma_point^2 + sigma_wander^2)  (a per-point 99.7 % bound)
// This is the error a unit calibrated without any systematic residual would still show at that
// point; acceptance reports it beside the specification, it never widens the specification.
// Left out: rate random walk and rate ramp beyond the rest record (their growth with T), the
// calibration's own estimation error (the constants' CRB, judged by the evaluation), temperature
// dependence of the noise (the rest record is taken at one temperature).
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
