#include "calib/executor/interlocks.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/sequence/sequence.h"
#include "common/imu_layout.h"

namespace adahrs::calib {
namespace {

constexpr double kDutyPerG = 0.04;              // ADXL210E nominal 4 %/g
constexpr double kGyroCountsPerDps = 20971.52;  // 16 * 2^19 / 5 V * 12.5 mV/(deg/s)
constexpr const char* kAxisNames[] = {"x_B", "y_B", "z_B"};

std::string AxisText(int orientation) {
  return fmt::format("{}{}", orientation % 10 == 1 ? "+" : "-", kAxisNames[orientation / 10 - 1]);
}

}  // namespace

InterlockThresholds ThresholdsForStation(const hil::Station& station,
                                         const InterlockThresholds& base) {
  InterlockThresholds t = base;
  const hil::InterlockSettings& s = station.interlocks;
  if (s.relative_tolerance_g) t.relative_tolerance_g = *s.relative_tolerance_g;
  if (s.first_check_margin_g) t.first_check_margin_g = *s.first_check_margin_g;
  if (s.min_gyro_response) t.min_gyro_response = *s.min_gyro_response;
  if (s.max_gyro_response) t.max_gyro_response = *s.max_gyro_response;
  return t;
}

int InterlockAttemptsForStation(const hil::Station& station, int base) {
  return station.interlocks.attempts.value_or(base);
}

Eigen::Vector3d UpAxis_B(int orientation) {
  if (!IsOrientationCode(orientation)) {
    throw std::invalid_argument(fmt::format("{} is not a fixture orientation code", orientation));
  }
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  up[orientation / 10 - 1] = orientation % 10 == 1 ? 1.0 : -1.0;
  return up;
}

Eigen::Vector3d NominalSpecificForce_B_g(const RawAverage& average) {
  // g_k = r_k . f_B with r_k = ±e_i; each axis has two channels, so f_i = Σ r_k,i g_k / Σ r_k,i².
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero(), count = Eigen::Vector3d::Zero();
  for (int ch = 0; ch < 6; ++ch) {
    const int chip = common::kImuChannels[ch].package, axis = common::kImuChannels[ch].package_axis;
    const Eigen::Vector3d r_B = common::NominalR_CB(chip).row(axis).transpose();
    const double g_k = average.duty_offset[ch] / kDutyPerG;
    weighted += r_B * g_k;
    count += r_B.cwiseAbs2();
  }
  return weighted.cwiseQuotient(count);
}

InterlockVerdict GravityVerdict(const RawAverage& average,
                                int orientation,
                                const GravityReference* reference,
                                const InterlockThresholds& thresholds) {
  const Eigen::Vector3d f_B_g = NominalSpecificForce_B_g(average);
  InterlockVerdict v;
  if (reference != nullptr) {
    const Eigen::Vector3d change_g = f_B_g - NominalSpecificForce_B_g(reference->average);
    const Eigen::Vector3d expected_g = UpAxis_B(orientation) - UpAxis_B(reference->orientation);
    const double worst_g = (change_g - expected_g).cwiseAbs().maxCoeff();
    v.ok = worst_g <= thresholds.relative_tolerance_g;
    v.detail = fmt::format(
        "f_B changed by ({:.2f}, {:.2f}, {:.2f}) g since orientation {}, expected ({:.0f}, {:.0f}, "
        "{:.0f}) g for orientation {} ({} up): off by {:.2f} g (tolerance {:g} g)",
        change_g.x(),
        change_g.y(),
        change_g.z(),
        reference->orientation,
        expected_g.x(),
        expected_g.y(),
        expected_g.z(),
        orientation,
        AxisText(orientation),
        worst_g,
        thresholds.relative_tolerance_g);
    return v;
  }
  int best = 0;
  double best_dot = -1e9;
  for (int code : kOrientationCodes) {
    const double dot = f_B_g.dot(UpAxis_B(code));
    if (dot > best_dot) {
      best_dot = dot;
      best = code;
    }
  }
  const double along_up_g = f_B_g.dot(UpAxis_B(orientation));
  v.ok = best_dot - along_up_g <= thresholds.first_check_margin_g;
  v.detail = fmt::format(
      "measured f_B = ({:.2f}, {:.2f}, {:.2f}) g over {} packets: {:.2f} g along the commanded "
      "orientation {} ({} up), {:.2f} g along orientation {} ({} up)",
      f_B_g.x(),
      f_B_g.y(),
      f_B_g.z(),
      average.packets,
      along_up_g,
      orientation,
      AxisText(orientation),
      best_dot,
      best,
      AxisText(best));
  return v;
}

InterlockVerdict GyroAxisVerdict(const RawAverage& rest,
                                 const RawAverage& jog,
                                 int orientation,
                                 double jog_rate_dps,
                                 const InterlockThresholds& thresholds) {
  const Eigen::Vector3d up = UpAxis_B(orientation);
  Eigen::Vector3d response_dps;
  for (int i = 0; i < 3; ++i)
    response_dps[i] = (jog.gyro_cnt[i] - rest.gyro_cnt[i]) / kGyroCountsPerDps;
  const Eigen::Vector3d expected_dps = jog_rate_dps * up;
  Eigen::Index moved = 0;
  response_dps.cwiseAbs().maxCoeff(&moved);
  const int axis = orientation / 10 - 1;
  const double ratio = response_dps[axis] / expected_dps[axis];
  InterlockVerdict v;
  v.ok = moved == axis && ratio >= thresholds.min_gyro_response &&
         ratio <= thresholds.max_gyro_response;
  v.detail = fmt::format(
      "table jog {:.0f} deg/s: gyro change (gx, gy, gz) = ({:.1f}, {:.1f}, {:.1f}) deg/s nominal; "
      "expected {:.0f} deg/s on g{} ({} up, orientation {})",
      jog_rate_dps,
      response_dps.x(),
      response_dps.y(),
      response_dps.z(),
      expected_dps[axis],
      "xyz"[axis],
      AxisText(orientation),
      orientation);
  return v;
}

}  // namespace adahrs::calib
