// Noise-characterisation estimators for sampled sensor records: overlapping Allan deviation and
// the one-sided power spectral density by Welch's method. Used by tests to check simulated noise
// against datasheet densities, and usable on recorded data.
//
// Conventions (stated once, used everywhere):
// - Samples are averages over consecutive intervals of `dt_s` (what a sampled rate gyro gives).
// - Allan variance follows IEEE Std 952-1997, Annex C: for cluster time tau = m·dt,
//     AVAR(tau) = 1 / (2 tau^2 (N - 2m)) · sum_k (theta[k+2m] - 2 theta[k+m] + theta[k])^2,
//   with theta the running integral of the samples (fully overlapping estimator).
// - PSDs are ONE-SIDED: integrating the PSD over [0, 1/(2 dt)] gives the variance. A white rate
//   noise with one-sided density N (unit/sqrt(Hz)) has AVAR(tau) = N^2 / (2 tau), i.e. Allan
//   deviation N / sqrt(2 tau). (IEEE 952's angle random walk coefficient, sigma = N_952/sqrt(tau),
//   uses the two-sided density: N_952 = N / sqrt(2).)
#pragma once

#include <cstddef>
#include <vector>

namespace adahrs::common {

/// One point of an Allan-deviation curve.
struct AllanPoint {
  double tau_s;           ///< cluster time m·dt, s
  double adev;            ///< Allan deviation, in the samples' unit
  size_t cluster_size;    ///< m, samples per cluster
  double relative_error;  ///< approximate 1-sigma relative error, 1/sqrt(2 (N/m - 1))
};

/// One bin of a one-sided PSD estimate.
struct PsdPoint {
  double f_hz;  ///< bin centre frequency, Hz
  double psd;   ///< one-sided PSD, (sample unit)^2 / Hz
};

/// Overlapping Allan deviation at one cluster size m (1 <= m <= (N-1)/2); throws
/// std::invalid_argument naming the offending values otherwise or if dt_s is not positive.
AllanPoint OverlappingAllanDeviationAt(const std::vector<double>& samples,
                                       double dt_s,
                                       size_t cluster_size);

/// Overlapping Allan deviation at cluster sizes spaced about `points_per_decade` per decade,
/// from m = 1 up to m = N/10 (so every point averages at least ~10 independent clusters).
std::vector<AllanPoint> OverlappingAllanDeviation(const std::vector<double>& samples,
                                                  double dt_s,
                                                  int points_per_decade = 10);

/// Welch one-sided PSD: Hann-windowed segments of `segment_length` samples (a power of two,
/// >= 8) with 50 % overlap, each segment's mean removed; bins 1 .. segment_length/2 (DC omitted).
/// Throws std::invalid_argument if the record is shorter than one segment.
std::vector<PsdPoint> WelchPsd(const std::vector<double>& samples,
                               double dt_s,
                               size_t segment_length);

/// Mean of the Welch one-sided PSD over the bins with 0 < f <= f_max_hz: the low-frequency level
/// of a spectrum that is flat there (e.g. white noise density squared). Throws if no bin is in
/// range.
double LowFrequencyPsd(const std::vector<double>& samples,
                       double dt_s,
                       size_t segment_length,
                       double f_max_hz);

}  // namespace adahrs::common
