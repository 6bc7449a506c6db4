#include "sensor_sim/gyro_bias_process.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adahrs::sensor_sim {
namespace {

// Each Gauss-Markov process is updated every T / kUpdatesPerCorrelationTime.
constexpr double kUpdatesPerCorrelationTime = 50.0;
// The rate random walk is updated every kRrwUpdateInterval_s.
constexpr double kRrwUpdateInterval_s = 1.0;
// Log-spaced tau points used to average the Allan deviation over the floor band.
constexpr int kFloorBandPoints = 201;
// Random streams of this process, derived from its seed.
constexpr uint64_t kBiasInstabilityStream = 0;
constexpr uint64_t kRateRandomWalkStream = 1;

// Allan variance of a Gauss-Markov process with unit variance and correlation time t_s.
double UnitGaussMarkovAvar(double tau_s, double t_s) {
  const double x = tau_s / t_s;
  return (2.0 * t_s / tau_s) * (1.0 - (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)) / (2.0 * x));
}

double UnitPolesAdev(double tau_s, double time_scale) {
  double avar = 0.0;
  for (double t_s : GyroBiasProcess::kCorrelationTimes_s) {
    avar += UnitGaussMarkovAvar(tau_s, time_scale * t_s);
  }
  return std::sqrt(avar);
}

// Mean over log(tau) in the floor band of the Allan deviation of unit-variance poles.
double UnitPolesFloor(double time_scale) {
  const double log_min = std::log(GyroBiasProcess::kFloorBandMin_s);
  const double log_max = std::log(GyroBiasProcess::kFloorBandMax_s);
  double sum = 0.0;
  for (int i = 0; i < kFloorBandPoints; ++i) {
    const double log_tau = log_min + (log_max - log_min) * i / (kFloorBandPoints - 1);
    sum += UnitPolesAdev(std::exp(log_tau), time_scale);
  }
  return sum / kFloorBandPoints;
}

int64_t FramesFor(double interval_s, double frame_period_s) {
  return std::max<int64_t>(1, std::llround(interval_s / frame_period_s));
}

}  // namespace

double GyroBiasProcess::PoleSigmaForFloor(double bias_instability_dps,
                                          double correlation_time_scale) {
  return bias_instability_dps / UnitPolesFloor(correlation_time_scale);
}

GyroBiasProcess::GyroBiasProcess(double bias_instability_dps,
                                 bool bias_instability_on,
                                 double rate_random_walk_dps_per_rts,
                                 bool rate_random_walk_on,
                                 double frame_period_s,
                                 uint64_t seed,
                                 double correlation_time_scale)
    : time_scale_(correlation_time_scale),
      bias_instability_on_(bias_instability_on && bias_instability_dps > 0.0),
      rate_random_walk_on_(rate_random_walk_on && rate_random_walk_dps_per_rts > 0.0),
      bi_rng_(common::Rng::Derive(seed, kBiasInstabilityStream)),
      rrw_rng_(common::Rng::Derive(seed, kRateRandomWalkStream)) {
  if (bias_instability_on_) {
    pole_sigma_dps_ = PoleSigmaForFloor(bias_instability_dps, time_scale_);
    for (size_t k = 0; k < poles_.size(); ++k) {
      Pole& pole = poles_[k];
      const double t_s = time_scale_ * kCorrelationTimes_s[k];
      pole.update_interval_frames = FramesFor(t_s / kUpdatesPerCorrelationTime, frame_period_s);
      const double h_s = static_cast<double>(pole.update_interval_frames) * frame_period_s;
      pole.phi = std::exp(-h_s / t_s);
      pole.innovation_dps = pole_sigma_dps_ * std::sqrt(1.0 - pole.phi * pole.phi);
      // Start in the stationary distribution, and stagger the first updates so the poles do not
      // all jump in the same frame.
      pole.bias_dps = pole_sigma_dps_ * bi_rng_.Normal();
      pole.frames_to_update = 1 + static_cast<int64_t>(k) % pole.update_interval_frames;
    }
  }
  if (rate_random_walk_on_) {
    rrw_update_interval_frames_ = FramesFor(kRrwUpdateInterval_s, frame_period_s);
    rrw_frames_to_update_ = rrw_update_interval_frames_;
    const double h_s = static_cast<double>(rrw_update_interval_frames_) * frame_period_s;
    rrw_step_dps_ = rate_random_walk_dps_per_rts * std::sqrt(h_s);
  }
  ScheduleNextUpdate();
  bias_dps_ = SumDps();
}

void GyroBiasProcess::ApplyDueUpdates() {
  const int64_t elapsed_frames = frames_between_updates_;
  if (bias_instability_on_) {
    for (Pole& pole : poles_) {
      pole.frames_to_update -= elapsed_frames;
      if (pole.frames_to_update == 0) {
        pole.frames_to_update = pole.update_interval_frames;
        pole.bias_dps = pole.phi * pole.bias_dps + pole.innovation_dps * bi_rng_.Normal();
      }
    }
  }
  if (rate_random_walk_on_) {
    rrw_frames_to_update_ -= elapsed_frames;
    if (rrw_frames_to_update_ == 0) {
      rrw_frames_to_update_ = rrw_update_interval_frames_;
      rrw_bias_dps_ += rrw_step_dps_ * rrw_rng_.Normal();
    }
  }
  ScheduleNextUpdate();
  bias_dps_ = SumDps();
}

void GyroBiasProcess::ScheduleNextUpdate() {
  int64_t next = std::numeric_limits<int64_t>::max();  // nothing enabled: never
  if (bias_instability_on_) {
    for (const Pole& pole : poles_) next = std::min(next, pole.frames_to_update);
  }
  if (rate_random_walk_on_) next = std::min(next, rrw_frames_to_update_);
  frames_between_updates_ = next;
  frames_to_next_update_ = next;
}

double GyroBiasProcess::SumDps() const {
  double sum_dps = rrw_bias_dps_;
  for (const Pole& pole : poles_) sum_dps += pole.bias_dps;
  return sum_dps;
}

double GyroBiasProcess::BiasInstabilityAdev(double tau_s) const {
  return pole_sigma_dps_ * UnitPolesAdev(tau_s, time_scale_);
}

}  // namespace adahrs::sensor_sim
