// Slow stochastic gyro bias: bias instability (a flicker, 1/f, floor in the Allan deviation) as
// the sum of kBiasInstabilityPoles first-order Gauss-Markov processes one decade apart (5, 50,
// 500, 5000 s) of equal variance, set so that the analytic Allan deviation averaged in log(tau)
// over 10...5000 s equals bias_instability_dps; and rate random walk, a step K sqrt(h) n every
// h = 1 s. Each process advanced exactly every T/50 and held in between. Starts at zero.
// Units: deg/s referred to the gyro input, one value per frame; times in s.
// Why four poles, the Allan variance formula (IEEE Std 952 Annex C; El-Sheimy et al. 2008), the
// hold's cost: docs/models/adxrs150.md ("Bias instability: what was chosen and why").
// Left out: bias-temperature coupling (see null tempco in adxrs150.h), turn-on bias
// repeatability.
#pragma once

#include <array>
#include <cstdint>

#include "common/random.h"

namespace adahrs::sensor_sim {

class GyroBiasProcess {
 public:
  static constexpr int kBiasInstabilityPoles = 4;
  static constexpr std::array<double, kBiasInstabilityPoles> kCorrelationTimes_s = {
      5.0, 50.0, 500.0, 5000.0};
  /// Band of tau over which `bias_instability_dps` is the mean Allan-deviation floor.
  static constexpr double kFloorBandMin_s = 10.0;
  static constexpr double kFloorBandMax_s = 5000.0;

  /// `bias_instability_dps` the Allan floor (0 or `bias_instability_on` false: none);
  /// `rate_random_walk_dps_per_rts` K in deg/s/sqrt(s). Streams are derived from `seed`.
  /// `correlation_time_scale` multiplies every pole's correlation time (1: the datasheet form
  /// above; a truth variant moves the corners, the floor over the band staying B).
  GyroBiasProcess(double bias_instability_dps,
                  bool bias_instability_on,
                  double rate_random_walk_dps_per_rts,
                  bool rate_random_walk_on,
                  double frame_period_s,
                  uint64_t seed,
                  double correlation_time_scale = 1.0);

  /// Advances one frame and returns the bias for that frame, deg/s.
  double Step() {
    // The bias changes only on frames where a pole or the walk is updated (at most every 10th
    // frame at 100 Hz); on the others it is the sum cached at the last update.
    if (--frames_to_next_update_ > 0) return bias_dps_;
    ApplyDueUpdates();
    return bias_dps_;
  }

  /// Analytic Allan deviation, deg/s, of the bias-instability part alone (for docs and tests).
  double BiasInstabilityAdev(double tau_s) const;

  /// Standard deviation of each Gauss-Markov process, deg/s.
  double pole_sigma_dps() const { return pole_sigma_dps_; }

  /// The standard deviation of each Gauss-Markov process whose sum has the Allan floor
  /// `bias_instability_dps` (for covariance models of the same process, e.g. calibration's).
  static double PoleSigmaForFloor(double bias_instability_dps, double correlation_time_scale = 1.0);

 private:
  struct Pole {
    double bias_dps = 0.0;
    double phi = 0.0;
    double innovation_dps = 0.0;
    int64_t update_interval_frames = 1;
    int64_t frames_to_update = 1;
  };

  // Advances every countdown by the frames since the last update, applies the updates that are
  // due (poles in order, then the walk: the same draws as updating frame by frame), schedules the
  // next one and refreshes bias_dps_.
  void ApplyDueUpdates();
  // The next update: the smallest countdown of an enabled process.
  void ScheduleNextUpdate();
  double SumDps() const;

  std::array<Pole, kBiasInstabilityPoles> poles_;
  double time_scale_ = 1.0;
  double pole_sigma_dps_ = 0.0;
  bool bias_instability_on_;
  bool rate_random_walk_on_;
  double rrw_bias_dps_ = 0.0;
  double rrw_step_dps_ = 0.0;
  int64_t rrw_update_interval_frames_ = 1;
  int64_t rrw_frames_to_update_ = 1;
  int64_t frames_between_updates_ = 1;  // from the last update to the next one
  int64_t frames_to_next_update_ = 1;
  double bias_dps_ = 0.0;  // sum of the poles and the walk since the last update
  common::Rng bi_rng_;
  common::Rng rrw_rng_;
};

}  // namespace adahrs::sensor_sim
