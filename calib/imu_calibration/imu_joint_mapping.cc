#include "calib/imu_calibration/imu_joint_mapping.h"

#include <algorithm>
#include <cmath>

#include "calib/imu_calibration/imu_constant_vector.h"
#include "common/units.h"

namespace adahrs::calib::joint_fit {

std::array<double, 4> ScaleFactorCubic(const ChannelModel& m,
                                       const Eigen::VectorXd& theta,
                                       double own_scale,
                                       const fm::TempSensorSpan& span) {
  constexpr int kPoints = 41;
  Eigen::MatrixXd a(kPoints, 4);
  Eigen::VectorXd f(kPoints);
  const double half = std::max(span.origin_cnt - span.min_cnt, span.max_cnt - span.origin_cnt);
  for (int i = 0; i < kPoints; ++i) {
    const double t = span.min_cnt + (span.max_cnt - span.min_cnt) * i / (kPoints - 1);
    const double tau = (t - kTempCentre_cnt) / kTempSpan_cnt;
    double delta = 0.0;
    for (int p = m.scale_order; p >= 1; --p) delta = (delta + theta[m.scale_index() + p - 1]) * tau;
    const double x = (t - span.origin_cnt) / half;
    a.row(i) << 1.0, x, x * x, x * x * x;
    f[i] = 1.0 / (1.0 + delta / own_scale);
  }
  const Eigen::Vector4d b = a.colPivHouseholderQr().solve(f);
  return {b[0], b[1] / half, b[2] / (half * half), b[3] / (half * half * half)};
}

void MapScaleTemperature(const std::array<ChannelModel, 9>& models,
                         const std::array<Eigen::VectorXd, 9>& theta,
                         const std::array<std::array<double, 2>, 3>& temp_span_cnt,
                         const Eigen::Matrix3d& cg,
                         fm::ImuCalibrationConstants* c) {
  fm::ImuScaleTemperature& st = c->scale_temperature;
  st.active = true;
  for (int s = 0; s < 3; ++s) {
    const double lo = temp_span_cnt[s][0], hi = temp_span_cnt[s][1];
    st.sensor[s] = {std::nearbyint(0.5 * (lo + hi)), lo, hi};
  }
  std::array<double, 9> own{};
  for (int ch = 0; ch < 9; ++ch) {
    const ChannelModel& m = models[ch];
    own[ch] = theta[ch][m.stimulus_index() + (m.gyro() ? ch - 6 : kAxisOfChannel[ch])];
    st.scale[ch] = ScaleFactorCubic(m, theta[ch], own[ch], st.sensor[m.sensor()]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    double q = 0.0;
    for (int ch : kPairOfAxis[axis]) {
      if (models[ch].quadratic) q -= 0.5 * theta[ch][models[ch].extra_index()] / own[ch];
    }
    st.accel_quadratic_per_g[axis] = q;
  }
  Eigen::Matrix3d gsens_dps_per_g = Eigen::Matrix3d::Zero();
  for (int g = 0; g < 3; ++g) {
    const ChannelModel& m = models[6 + g];
    if (!m.g_sensitivity) continue;
    for (int a = 0; a < 3; ++a)
      gsens_dps_per_g(g, a) = theta[6 + g][m.extra_index() + a] / own[6 + g];
  }
  const Eigen::Matrix3d gs = -cg * gsens_dps_per_g / common::kStandardGravity_mps2;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) st.gs_dps_per_mps2[r][k] = gs(r, k);
  }
}

fm::ImuCalibrationConstants Map(const std::array<ChannelModel, 9>& models,
                                const std::array<Eigen::VectorXd, 9>& theta,
                                const std::array<std::array<double, 2>, 3>& temp_span_cnt) {
  fm::ImuCalibrationConstants c;
  const double tc = kTempCentre_cnt, ts = kTempSpan_cnt;
  // xi(t) = sum_{j>=1} alpha_j tau^j, tau = (t - tc)/ts, re-expanded in raw counts by Horner's
  // rule on polynomials in t: k <- k * (t - tc)/ts + alpha_j for j = order ... 0 (alpha_0 = 0:
  // the offset is the channel's o_i or null, not part of xi).
  auto thermal = [&](int ch, double* offset) {
    const ChannelModel& m = models[ch];
    const Eigen::VectorXd& th = theta[ch];
    std::array<double, kMaxThermalOrder + 1> k{};  // k[i]: coefficient of t^i
    for (int j = m.order; j >= 0; --j) {
      for (int i = kMaxThermalOrder; i >= 1; --i) k[i] = (k[i - 1] - tc * k[i]) / ts;
      k[0] = -tc * k[0] / ts + (j >= 1 ? th[j] : 0.0);
    }
    c.thermal[ch].temp_sensor = m.sensor();
    c.thermal[ch].k = k;
    c.thermal[ch].temp_min_cnt = temp_span_cnt[m.sensor()][0];
    c.thermal[ch].temp_max_cnt = temp_span_cnt[m.sensor()][1];
    *offset = th[0];
  };
  std::array<Eigen::Vector3d, 6> m_over_s;
  for (int ch = 0; ch < 6; ++ch) {
    double offset = 0.0;
    thermal(ch, &offset);
    const int k = 1 + models[ch].order;
    const Eigen::Vector3d m(theta[ch][k], theta[ch][k + 1], theta[ch][k + 2]);
    const double s = m[kAxisOfChannel[ch]];
    c.accel[ch] = {offset, s};
    m_over_s[ch] = m / s;
  }
  Eigen::Matrix3d pair;
  for (int axis = 0; axis < 3; ++axis) {
    pair.row(axis) =
        0.5 * (m_over_s[kPairOfAxis[axis][0]] + m_over_s[kPairOfAxis[axis][1]]).transpose();
  }
  const Eigen::Matrix3d ca = common::kStandardGravity_mps2 * pair.inverse();
  Eigen::Matrix3d n_rows;
  for (int g = 0; g < 3; ++g) {
    const int ch = 6 + g;
    double null_cnt = 0.0;
    thermal(ch, &null_cnt);
    const int k = 1 + models[ch].order;
    const Eigen::Vector3d n(theta[ch][k], theta[ch][k + 1], theta[ch][k + 2]);
    const double q2 = theta[ch][k + 3], q3 = theta[ch][k + 4];
    // l: least squares of w on x = d / kDScale over the rated span.
    constexpr int kRates = 61;
    Eigen::MatrixXd a(kRates, 3);
    Eigen::VectorXd w(kRates);
    for (int i = 0; i < kRates; ++i) {
      const double rate = -kInverseCubicSpan_dps + 2.0 * kInverseCubicSpan_dps * i / (kRates - 1);
      const double x = (n[g] * rate + q2 * rate * rate + q3 * rate * rate * rate) / kDScale_cnt;
      a.row(i) << x, x * x, x * x * x;
      w[i] = rate;
    }
    const Eigen::Vector3d lambda = a.colPivHouseholderQr().solve(w);
    c.gyro[g] = {null_cnt,
                 {0.0,
                  lambda[0] / kDScale_cnt,
                  lambda[1] / (kDScale_cnt * kDScale_cnt),
                  lambda[2] / (kDScale_cnt * kDScale_cnt * kDScale_cnt)}};
    n_rows.row(g) = n.transpose() / n[g];
  }
  const Eigen::Matrix3d cg = n_rows.inverse();
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c.ca_mps2_per_g[r][k] = ca(r, k);
      c.cg[r][k] = cg(r, k);
    }
  }
  if (HasFormat3Terms(models)) MapScaleTemperature(models, theta, temp_span_cnt, cg, &c);
  return c;
}

Eigen::MatrixXd Propagate(const std::array<ChannelModel, 9>& models,
                          const std::array<Eigen::VectorXd, 9>& theta,
                          const std::array<Eigen::MatrixXd, 9>& cov,
                          const std::array<std::array<double, 2>, 3>& temp_span_cnt) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(kImuFirmwareNumbers, kImuFirmwareNumbers);
  for (int ch = 0; ch < 9; ++ch) {
    const long p = theta[ch].size();
    Eigen::MatrixXd jac(kImuFirmwareNumbers, p);
    for (long j = 0; j < p; ++j) {
      const double h = std::max(1e-3 * std::sqrt(std::max(cov[ch](j, j), 0.0)),
                                1e-12 * std::max(1.0, std::abs(theta[ch][j])));
      std::array<Eigen::VectorXd, 9> plus = theta, minus = theta;
      plus[ch][j] += h;
      minus[ch][j] -= h;
      jac.col(j) = (FlattenConstants(Map(models, plus, temp_span_cnt)) -
                    FlattenConstants(Map(models, minus, temp_span_cnt))) /
                   (2.0 * h);
    }
    out += jac * cov[ch] * jac.transpose();
  }
  return out;
}

}  // namespace adahrs::calib::joint_fit
