#include "common/allan.h"

#include <cmath>
#include <complex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace adahrs::common {
namespace {

[[noreturn]] void Invalid(const std::string& what) { throw std::invalid_argument(what); }

void CheckDt(double dt_s, const char* function) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    std::ostringstream s;
    s << function << ": dt_s must be positive and finite, got " << dt_s;
    Invalid(s.str());
  }
}

// In-place iterative radix-2 decimation-in-time FFT; x.size() is a power of two.
void Fft(std::vector<std::complex<double>>& x) {
  const size_t n = x.size();
  for (size_t i = 1, j = 0; i < n; ++i) {
    size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(x[i], x[j]);
  }
  for (size_t len = 2; len <= n; len <<= 1) {
    const double angle_rad = -2.0 * kPi / static_cast<double>(len);
    const std::complex<double> w_len(std::cos(angle_rad), std::sin(angle_rad));
    for (size_t start = 0; start < n; start += len) {
      std::complex<double> w(1.0, 0.0);
      for (size_t k = 0; k < len / 2; ++k) {
        const std::complex<double> even = x[start + k];
        const std::complex<double> odd = x[start + k + len / 2] * w;
        x[start + k] = even + odd;
        x[start + k + len / 2] = even - odd;
        w *= w_len;
      }
    }
  }
}

}  // namespace

AllanPoint OverlappingAllanDeviationAt(const std::vector<double>& samples,
                                       double dt_s,
                                       size_t cluster_size) {
  CheckDt(dt_s, "OverlappingAllanDeviationAt");
  const size_t n = samples.size();
  const size_t m = cluster_size;
  if (m < 1 || n < 2 * m + 1) {
    std::ostringstream s;
    s << "OverlappingAllanDeviationAt: cluster size " << m
      << " needs 1 <= m <= (N-1)/2 with N = " << n << " samples";
    Invalid(s.str());
  }
  // theta[k] = dt · sum of the first k samples (the integrated quantity, e.g. angle).
  std::vector<double> theta(n + 1, 0.0);
  for (size_t k = 0; k < n; ++k) theta[k + 1] = theta[k] + samples[k] * dt_s;
  const double tau_s = static_cast<double>(m) * dt_s;
  double sum = 0.0;
  const size_t terms = n + 1 - 2 * m;
  for (size_t k = 0; k < terms; ++k) {
    const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
    sum += d * d;
  }
  const double avar = sum / (2.0 * tau_s * tau_s * static_cast<double>(terms));
  const double clusters = static_cast<double>(n) / static_cast<double>(m);
  return AllanPoint{tau_s, std::sqrt(avar), m, 1.0 / std::sqrt(2.0 * (clusters - 1.0))};
}

std::vector<AllanPoint> OverlappingAllanDeviation(const std::vector<double>& samples,
                                                  double dt_s,
                                                  int points_per_decade) {
  CheckDt(dt_s, "OverlappingAllanDeviation");
  if (points_per_decade < 1) {
    Invalid("OverlappingAllanDeviation: points_per_decade must be >= 1, got " +
            std::to_string(points_per_decade));
  }
  const size_t m_max = samples.size() / 10;
  if (m_max < 1) {
    Invalid("OverlappingAllanDeviation: need at least 10 samples, got " +
            std::to_string(samples.size()));
  }
  std::vector<AllanPoint> curve;
  size_t last_m = 0;
  for (int i = 0;; ++i) {
    const double m_real = std::pow(10.0, static_cast<double>(i) / points_per_decade);
    const auto m = static_cast<size_t>(std::llround(m_real));
    if (m > m_max) break;
    if (m == last_m) continue;
    curve.push_back(OverlappingAllanDeviationAt(samples, dt_s, m));
    last_m = m;
  }
  return curve;
}

std::vector<PsdPoint> WelchPsd(const std::vector<double>& samples,
                               double dt_s,
                               size_t segment_length) {
  CheckDt(dt_s, "WelchPsd");
  const size_t l = segment_length;
  if (l < 8 || (l & (l - 1)) != 0) {
    Invalid("WelchPsd: segment_length must be a power of two >= 8, got " + std::to_string(l));
  }
  if (samples.size() < l) {
    Invalid("WelchPsd: record of " + std::to_string(samples.size()) +
            " samples is shorter than one segment of " + std::to_string(l));
  }
  // Periodic Hann window; the PSD is normalised by sum(w^2) so that a white sequence of variance
  // s^2 gives the one-sided level 2 s^2 dt.
  std::vector<double> window(l);
  double window_power = 0.0;
  for (size_t i = 0; i < l; ++i) {
    window[i] = 0.5 - 0.5 * std::cos(2.0 * kPi * static_cast<double>(i) / static_cast<double>(l));
    window_power += window[i] * window[i];
  }
  std::vector<double> accumulated(l / 2 + 1, 0.0);
  std::vector<std::complex<double>> buffer(l);
  size_t segments = 0;
  for (size_t start = 0; start + l <= samples.size(); start += l / 2, ++segments) {
    double mean = 0.0;
    for (size_t i = 0; i < l; ++i) mean += samples[start + i];
    mean /= static_cast<double>(l);
    for (size_t i = 0; i < l; ++i) buffer[i] = (samples[start + i] - mean) * window[i];
    Fft(buffer);
    for (size_t k = 1; k <= l / 2; ++k) accumulated[k] += std::norm(buffer[k]);
  }
  std::vector<PsdPoint> psd;
  psd.reserve(l / 2);
  const double df_hz = 1.0 / (static_cast<double>(l) * dt_s);
  for (size_t k = 1; k <= l / 2; ++k) {
    const double one_sided = (k == l / 2) ? 1.0 : 2.0;  // the Nyquist bin has no mirror image
    psd.push_back(PsdPoint{static_cast<double>(k) * df_hz,
                           one_sided * accumulated[k] * dt_s / (window_power * segments)});
  }
  return psd;
}

double LowFrequencyPsd(const std::vector<double>& samples,
                       double dt_s,
                       size_t segment_length,
                       double f_max_hz) {
  const std::vector<PsdPoint> psd = WelchPsd(samples, dt_s, segment_length);
  double sum = 0.0;
  size_t bins = 0;
  for (const PsdPoint& p : psd) {
    if (p.f_hz <= f_max_hz) {
      sum += p.psd;
      ++bins;
    }
  }
  if (bins == 0) {
    std::ostringstream s;
    s << "LowFrequencyPsd: no bin below f_max_hz = " << f_max_hz << " Hz (bin spacing "
      << psd.front().f_hz << " Hz)";
    Invalid(s.str());
  }
  return sum / static_cast<double>(bins);
}

}  // namespace adahrs::common
