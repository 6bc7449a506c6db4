#include "calib/executor/chamber_eta.h"

#include <algorithm>
#include <cmath>

namespace adahrs::calib {

void ChamberEta::Observe(double now_s, double pv_c, double inside_since_s) {
  window_.emplace_back(now_s, pv_c);
  while (window_.size() > 2 && now_s - window_[1].first >= kChamberRateWindowS) {
    window_.pop_front();
  }
  inside_since_s_ = inside_since_s;
}

namespace {

// The least-squares line y = a + b (t - t0) through (t, y) and its residual sum of squares, the
// residuals taken through `back` (the identity, or exp for a line fitted to ln e).
struct Line {
  double a = 0.0, b = 0.0, rss = 0.0;
};

template <typename Y, typename Back>
Line FitLine(const std::deque<std::pair<double, double>>& window, double t0, Y y, Back back) {
  double n = 0.0, st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0;
  for (const auto& [t_s, pv_c] : window) {
    const double t = t_s - t0, v = y(pv_c);
    n += 1.0;
    st += t;
    sy += v;
    stt += t * t;
    sty += t * v;
  }
  Line line;
  const double det = n * stt - st * st;
  if (det <= 0.0) return line;
  line.b = (n * sty - st * sy) / det;
  line.a = (sy - line.b * st) / n;
  for (const auto& [t_s, pv_c] : window) {
    const double r = back(y(pv_c)) - back(line.a + line.b * (t_s - t0));
    line.rss += r * r;
  }
  return line;
}

}  // namespace

std::optional<double> ChamberEta::RemainingS() const {
  if (window_.empty()) return std::nullopt;
  const auto& [now_s, pv_c] = window_.back();
  if (inside_since_s_ >= 0.0) return std::max(0.0, soak_s_ - (now_s - inside_since_s_));
  const auto& [then_s, then_c] = window_.front();
  const double span_s = now_s - then_s;
  const auto distance = [&](double c) { return std::abs(target_c_ - c); };
  if (span_s < kChamberMinWindowS || window_.size() < kChamberMinReadings ||
      distance(then_c) - distance(pv_c) < kChamberMinApproachC) {
    return std::nullopt;
  }
  const auto identity = [](double v) { return v; };
  const Line ramp = FitLine(window_, now_s, distance, identity);
  // ln e: the settling law is a straight line there (e > 0: the approach above is > 0.2 degC).
  const auto log_distance = [&](double c) { return std::log(std::max(distance(c), 1e-3)); };
  const auto exp = [](double v) { return std::exp(v); };
  const Line settle = FitLine(window_, now_s, log_distance, exp);
  if (ramp.b >= 0.0) return std::nullopt;  // not approaching, by the fit
  const double e_now = ramp.a;             // the fitted distance now (t - t0 = 0)
  if (e_now <= band_c_) return soak_s_;
  // The settling law must fit clearly better: over a ramp both fit a short or sparse window about
  // as well, and the exponential then extrapolates a tail the ramp does not have.
  if (band_c_ > 0.0 && settle.b < 0.0 && settle.rss < kChamberSettleRssRatio * ramp.rss) {
    return (settle.a - std::log(band_c_)) / -settle.b + soak_s_;
  }
  return (e_now - band_c_) / -ramp.b + soak_s_;
}

}  // namespace adahrs::calib
