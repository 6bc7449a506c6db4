#include "diagnosis/rate_ripple.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>

#include "common/median.h"

namespace adahrs::diagnosis {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kChi2TwoMedian = 1.3862943611198906;  // 2 ln 2
constexpr int kLockInColumns = 4;
constexpr int kMinLockInRows = 8;

// k^2 from every segment but `skip` (-1: none), their standard errors scaled by sqrt(inflation).
double RatioSquared(const std::vector<RippleSegment>& s,
                    double cnt_per_dps,
                    double inflation,
                    int skip) {
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < s.size(); ++i) {
    if (static_cast<int>(i) == skip) continue;
    const LockIn& l = s[i].at_revolution;
    const double r2 = l.cos_amp * l.cos_amp + l.sin_amp * l.sin_amp;
    num += r2 - 2.0 * l.se * l.se * inflation;
    const double a = s[i].rate_dps * cnt_per_dps;
    den += a * a;
  }
  return den > 0.0 ? num / den : 0.0;
}

// Noncentrality a chi^2 test of `df` degrees of freedom at `critical` needs for the power of z:
// the normal approximation of the noncentral chi^2 (mean df + lambda, variance 2 (df + 2 lambda)).
double NeededNoncentrality(double df, double critical, double power_z) {
  double lambda = std::max(0.0, critical - df);
  for (int i = 0; i < 50; ++i)
    lambda = std::max(0.0, critical - df + power_z * std::sqrt(2.0 * (df + 2.0 * lambda)));
  return lambda;
}

}  // namespace

std::optional<LockIn> FitLockIn(const std::vector<double>& t_s,
                                const std::vector<double>& y,
                                double frequency_hz) {
  const size_t n = std::min(t_s.size(), y.size());
  if (n < static_cast<size_t>(kMinLockInRows)) return std::nullopt;
  const double t_mean = std::accumulate(t_s.begin(), t_s.begin() + static_cast<long>(n), 0.0) /
                        static_cast<double>(n);
  const double y_mean =
      std::accumulate(y.begin(), y.begin() + static_cast<long>(n), 0.0) / static_cast<double>(n);
  Eigen::Matrix4d xtx = Eigen::Matrix4d::Zero();
  Eigen::Vector4d xty = Eigen::Vector4d::Zero();
  double yty = 0.0;
  const double w = 2.0 * kPi * frequency_hz;
  for (size_t i = 0; i < n; ++i) {
    const double t = t_s[i] - t_mean;
    const Eigen::Vector4d x(1.0, t, std::cos(w * t_s[i]), std::sin(w * t_s[i]));
    const double v = y[i] - y_mean;
    xtx.noalias() += x * x.transpose();
    xty += x * v;
    yty += v * v;
  }
  const Eigen::LDLT<Eigen::Matrix4d> ldlt(xtx);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::Vector4d theta = ldlt.solve(xty);
  const double rss = std::max(0.0, yty - theta.dot(xty));
  const double sigma2 = rss / static_cast<double>(n - kLockInColumns);
  const Eigen::Matrix4d cov = ldlt.solve(Eigen::Matrix4d::Identity()) * sigma2;
  const double se = std::sqrt(0.5 * (cov(2, 2) + cov(3, 3)));
  if (!(se > 0.0) || !std::isfinite(se)) return std::nullopt;
  return LockIn{frequency_hz, theta[2], theta[3], se};
}

std::vector<double> RippleControlRatios() { return {0.55, 0.65, 0.75, 1.3, 1.45, 1.6}; }

std::optional<RippleSegment> MeasureRipple(int segment,
                                           double rate_dps,
                                           const std::vector<double>& t_s,
                                           const std::vector<double>& y) {
  const double f = std::abs(rate_dps) / 360.0;
  if (f < kMinRippleHz || t_s.size() < 2) return std::nullopt;
  if ((t_s.back() - t_s.front()) * f < kMinRippleCycles) return std::nullopt;
  const std::optional<LockIn> at = FitLockIn(t_s, y, f);
  if (!at) return std::nullopt;
  RippleSegment s{segment, rate_dps, *at, {}};
  for (double r : RippleControlRatios()) {
    if (const std::optional<LockIn> c = FitLockIn(t_s, y, f * r)) s.controls.push_back(*c);
  }
  return s;
}

RippleTest TestRipple(const std::vector<RippleSegment>& segments,
                      double cnt_per_dps,
                      double alpha,
                      double power_z) {
  RippleTest out;
  out.segments = static_cast<int>(segments.size());
  if (segments.empty() || !(cnt_per_dps > 0.0)) {
    out.note =
        "no rate segment with this gyro on the table axis turning at 36 deg/s (0.1 Hz) or more for "
        "3 turns";
    return out;
  }
  std::vector<double> control;
  for (const RippleSegment& s : segments) {
    for (const LockIn& c : s.controls) control.push_back(c.Statistic());
  }
  out.inflation = control.empty() ? 1.0 : std::max(1.0, common::Median(control) / kChi2TwoMedian);
  double statistic = 0.0, signal_per_k2 = 0.0;
  for (const RippleSegment& s : segments) {
    statistic += s.at_revolution.Statistic() / out.inflation;
    const double a = s.rate_dps * cnt_per_dps;
    signal_per_k2 += a * a / (s.at_revolution.se * s.at_revolution.se * out.inflation);
  }
  const double df = 2.0 * static_cast<double>(segments.size());
  const boost::math::chi_squared chi2(df);
  out.testable = true;
  out.p_value = boost::math::cdf(boost::math::complement(chi2, statistic));
  const double critical = boost::math::quantile(boost::math::complement(chi2, alpha));
  out.smallest_detectable_ratio =
      std::sqrt(NeededNoncentrality(df, critical, power_z) / signal_per_k2);

  const double k2 = RatioSquared(segments, cnt_per_dps, out.inflation, -1);
  out.ratio = std::sqrt(std::max(0.0, k2));
  double var_k2 = 0.0, den = 0.0;
  for (const RippleSegment& s : segments) {
    const double a = s.rate_dps * cnt_per_dps;
    const double se2 = s.at_revolution.se * s.at_revolution.se * out.inflation;
    const double amp = out.ratio * std::abs(a);
    var_k2 += 4.0 * se2 * amp * amp + 4.0 * se2 * se2;
    den += a * a;
  }
  const double se_k2 = std::sqrt(var_k2) / den;
  out.ratio_se = out.ratio > 0.0 ? se_k2 / (2.0 * out.ratio) : std::sqrt(se_k2);

  double before = 0.0, after = 0.0;
  std::vector<std::pair<double, int>> strength;
  for (size_t i = 0; i < segments.size(); ++i) {
    const LockIn& l = segments[i].at_revolution;
    const double r = std::hypot(l.cos_amp, l.sin_amp);
    const double predicted =
        std::sqrt(std::max(
            0.0, RatioSquared(segments, cnt_per_dps, out.inflation, static_cast<int>(i)))) *
        std::abs(segments[i].rate_dps) * cnt_per_dps;
    before += r * r;
    after += (r - predicted) * (r - predicted);
    strength.push_back({r, segments[i].segment});
  }
  out.held_out_rms_before_dps =
      std::sqrt(before / static_cast<double>(segments.size())) / cnt_per_dps;
  out.held_out_rms_after_dps =
      std::sqrt(after / static_cast<double>(segments.size())) / cnt_per_dps;
  std::sort(strength.rbegin(), strength.rend());
  for (size_t i = 0; i < std::min<size_t>(3, strength.size()); ++i)
    out.strongest_segments.push_back(strength[i].second);
  return out;
}

}  // namespace adahrs::diagnosis
