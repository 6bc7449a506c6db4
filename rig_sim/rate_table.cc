#include "rig_sim/rate_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace adahrs::rig_sim {
namespace {

using common::DegToRad;
using common::kPi;
using common::RadToDeg;

constexpr double kDegPerRev = 360.0;
// Below this the exponential tail of a stopped platter is called rest (far below any band).
constexpr double kRestRate_dps = 1e-12;
// A position reference this close to its target has arrived (rounding of the braking curve).
constexpr double kArrived_deg = 1e-9;

void Require(bool ok, const char* name, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string("RateTable: parameter ") + name + " = " +
                                std::to_string(value) + " is not usable");
  }
}

double Wrap360(double angle_deg) {
  double wrapped = std::fmod(angle_deg, kDegPerRev);
  if (wrapped < 0.0) wrapped += kDegPerRev;
  return wrapped >= kDegPerRev ? 0.0 : wrapped;
}

double Sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

RateTable::RateTable(const RateTableParams& params, double initial_angle_deg)
    : params_(params),
      accel_dps2_(params.accel_dps2),
      ref_angle_deg_(initial_angle_deg),
      angle_smooth_deg_(initial_angle_deg) {
  Require(params.max_rate_dps > 0.0, "max_rate_dps", params.max_rate_dps);
  Require(params.max_accel_dps2 > 0.0, "max_accel_dps2", params.max_accel_dps2);
  Require(params.accel_dps2 > 0.0 && params.accel_dps2 <= params.max_accel_dps2,
          "accel_dps2",
          params.accel_dps2);
  Require(params.rate_loop_tau_s > 0.0, "rate_loop_tau_s", params.rate_loop_tau_s);
  Require(params.move_rate_dps > 0.0 && params.move_rate_dps <= params.max_rate_dps,
          "move_rate_dps",
          params.move_rate_dps);
  Require(params.rate_ripple_ratio >= 0.0 && params.rate_ripple_ratio < 0.01,
          "rate_ripple_ratio",
          params.rate_ripple_ratio);
  Require(params.at_rate_band_dps > 0.0, "at_rate_band_dps", params.at_rate_band_dps);
  Require(params.in_position_band_deg > 0.0, "in_position_band_deg", params.in_position_band_deg);
  Require(params.coast_tau_s > 0.0, "coast_tau_s", params.coast_tau_s);
  Require(std::isfinite(initial_angle_deg), "initial_angle_deg", initial_angle_deg);
}

void RateTable::AdvanceTo(double time_s) {
  // The small allowance keeps a time that is a whole number of ticks from losing one to rounding.
  const auto target_ticks = static_cast<long long>(std::floor(time_s / kTick_s + 1e-6));
  while (ticks_ < target_ticks) {
    if (Quiescent()) {
      ticks_ = target_ticks;
      return;
    }
    Tick();
    ++ticks_;
  }
}

bool RateTable::Quiescent() const {
  const bool at_rest = rate_smooth_dps_ == 0.0 && ref_rate_dps_ == 0.0;
  return at_rest && ((mode_ == Mode::kRate && commanded_rate_dps_ == 0.0 && !braking_) ||
                     (mode_ == Mode::kPosition && ref_angle_deg_ == target_angle_deg_) ||
                     mode_ == Mode::kCoast);
}

void RateTable::FollowSegment(double r0_dps, double slope_dps2, double dt_s) {
  if (dt_s <= 0.0) return;
  if (stalled_) {
    rate_smooth_dps_ = 0.0;
    return;
  }
  const double tau_s = params_.rate_loop_tau_s;
  const double decay = std::exp(-dt_s / tau_s);
  const double c_dps = rate_smooth_dps_ - r0_dps + slope_dps2 * tau_s;
  angle_smooth_deg_ += r0_dps * dt_s + 0.5 * slope_dps2 * dt_s * dt_s - slope_dps2 * tau_s * dt_s +
                       c_dps * tau_s * (1.0 - decay);
  rate_smooth_dps_ = r0_dps + slope_dps2 * dt_s - slope_dps2 * tau_s + c_dps * decay;
}

void RateTable::Tick() {
  const double dt_s = kTick_s;
  switch (mode_) {
    case Mode::kCoast: {
      if (stalled_) {
        rate_smooth_dps_ = 0.0;
      } else {
        const double decay = std::exp(-dt_s / params_.coast_tau_s);
        angle_smooth_deg_ += rate_smooth_dps_ * params_.coast_tau_s * (1.0 - decay);
        rate_smooth_dps_ *= decay;
        if (std::fabs(rate_smooth_dps_) < kRestRate_dps) rate_smooth_dps_ = 0.0;
      }
      ref_rate_dps_ = rate_smooth_dps_;
      ref_angle_deg_ = LeadAngle();
      break;
    }
    case Mode::kRate: {
      const double accel_dps2 = braking_ ? params_.max_accel_dps2 : accel_dps2_;
      const double r0_dps = ref_rate_dps_;
      const double gap_dps = commanded_rate_dps_ - r0_dps;
      const double slope_dps2 = Sign(gap_dps) * accel_dps2;
      if (std::fabs(gap_dps) <= accel_dps2 * dt_s) {
        // The reference reaches the command inside this tick: ramp, then hold.
        const double ramp_s = std::fabs(gap_dps) / accel_dps2;
        FollowSegment(r0_dps, slope_dps2, ramp_s);
        FollowSegment(commanded_rate_dps_, 0.0, dt_s - ramp_s);
        ref_rate_dps_ = commanded_rate_dps_;
      } else {
        FollowSegment(r0_dps, slope_dps2, dt_s);
        ref_rate_dps_ = r0_dps + slope_dps2 * dt_s;
      }
      if (ref_rate_dps_ == 0.0 && std::fabs(rate_smooth_dps_) < kRestRate_dps) {
        rate_smooth_dps_ = 0.0;
      }
      if (braking_ && ref_rate_dps_ == 0.0 && rate_smooth_dps_ == 0.0) {
        braking_ = false;
        mode_ = Mode::kCoast;
      }
      ref_angle_deg_ = LeadAngle();
      break;
    }
    case Mode::kPosition: {
      const double accel_dps2 = accel_dps2_;
      const double error_deg = target_angle_deg_ - ref_angle_deg_;
      const double speed_dps = std::min({params_.move_rate_dps,
                                         std::sqrt(2.0 * accel_dps2 * std::fabs(error_deg)),
                                         std::fabs(error_deg) / dt_s});
      const double r0_dps = ref_rate_dps_;
      const double r1_dps =
          r0_dps +
          std::clamp(Sign(error_deg) * speed_dps - r0_dps, -accel_dps2 * dt_s, accel_dps2 * dt_s);
      FollowSegment(r0_dps, (r1_dps - r0_dps) / dt_s, dt_s);
      ref_angle_deg_ += 0.5 * (r0_dps + r1_dps) * dt_s;
      ref_rate_dps_ = r1_dps;
      if (std::fabs(target_angle_deg_ - ref_angle_deg_) < kArrived_deg &&
          std::fabs(r1_dps) <= accel_dps2 * dt_s) {
        ref_angle_deg_ = target_angle_deg_;
        ref_rate_dps_ = 0.0;
      }
      if (ref_rate_dps_ == 0.0 && std::fabs(rate_smooth_dps_) < kRestRate_dps) {
        rate_smooth_dps_ = 0.0;
      }
      break;
    }
    case Mode::kSine: {
      // Reference angle θ0 + A·(1 − cos ωτ), rate A·ω·sin ωτ (deg/s with A in deg, ω in rad/s),
      // followed as a straight line across each tick.
      const double omega_radps = 2.0 * kPi * sine_frequency_hz_;
      const double t0_s = sine_elapsed_s_;
      const double t1_s = std::min(t0_s + dt_s, sine_duration_s_);
      const double r0_dps = sine_amplitude_deg_ * omega_radps * std::sin(omega_radps * t0_s);
      const double r1_dps = sine_amplitude_deg_ * omega_radps * std::sin(omega_radps * t1_s);
      FollowSegment(r0_dps, (r1_dps - r0_dps) / (t1_s - t0_s), t1_s - t0_s);
      FollowSegment(r1_dps, 0.0, dt_s - (t1_s - t0_s));
      sine_elapsed_s_ = t1_s;
      ref_rate_dps_ = r1_dps;
      ref_angle_deg_ = sine_start_deg_ + sine_amplitude_deg_ * (1.0 - std::cos(omega_radps * t1_s));
      if (t1_s >= sine_duration_s_) {
        // After the last cycle the controller holds the start position.
        mode_ = Mode::kPosition;
        target_angle_deg_ = sine_start_deg_;
        ref_angle_deg_ = sine_start_deg_;
        ref_rate_dps_ = 0.0;
      }
      break;
    }
  }
}

double RateTable::LeadAngle() const {
  return angle_smooth_deg_ + params_.rate_loop_tau_s * rate_smooth_dps_;
}

RateTableRefusal RateTable::Jog(double rate_dps) {
  if (interlock_open_) return RateTableRefusal::kInterlockOpen;
  if (!servo_on_) return RateTableRefusal::kServoOff;
  if (!(std::fabs(rate_dps) <= params_.max_rate_dps)) return RateTableRefusal::kBeyondLimit;
  mode_ = Mode::kRate;
  commanded_rate_dps_ = rate_dps;
  return RateTableRefusal::kNone;
}

RateTableRefusal RateTable::Stop() {
  if (servo_on_) {
    mode_ = Mode::kRate;
    commanded_rate_dps_ = 0.0;
  }
  return RateTableRefusal::kNone;
}

RateTableRefusal RateTable::MoveTo(double angle_deg) {
  if (interlock_open_) return RateTableRefusal::kInterlockOpen;
  if (!servo_on_) return RateTableRefusal::kServoOff;
  if (!std::isfinite(angle_deg)) return RateTableRefusal::kBeyondLimit;
  double delta_deg = Wrap360(angle_deg) - Wrap360(angle_smooth_deg_);
  if (delta_deg > 0.5 * kDegPerRev) delta_deg -= kDegPerRev;
  if (delta_deg <= -0.5 * kDegPerRev) delta_deg += kDegPerRev;
  if (mode_ != Mode::kPosition) ref_angle_deg_ = LeadAngle();
  target_angle_deg_ = angle_smooth_deg_ + delta_deg;
  mode_ = Mode::kPosition;
  commanded_rate_dps_ = 0.0;
  return RateTableRefusal::kNone;
}

RateTableRefusal RateTable::SetAcceleration(double accel_dps2) {
  if (!(accel_dps2 > 0.0 && accel_dps2 <= params_.max_accel_dps2)) {
    return RateTableRefusal::kBeyondLimit;
  }
  accel_dps2_ = accel_dps2;
  return RateTableRefusal::kNone;
}

RateTableRefusal RateTable::SetServo(bool on) {
  if (on == servo_on_) return RateTableRefusal::kNone;
  if (on) {
    if (interlock_open_) return RateTableRefusal::kInterlockOpen;
    // Bumpless engagement: hold the rate the platter has, until a command says otherwise.
    servo_on_ = true;
    mode_ = Mode::kRate;
    ref_rate_dps_ = rate_smooth_dps_;
    commanded_rate_dps_ = rate_smooth_dps_;
  } else {
    servo_on_ = false;
    braking_ = false;
    mode_ = Mode::kCoast;
    commanded_rate_dps_ = 0.0;
  }
  return RateTableRefusal::kNone;
}

RateTableRefusal RateTable::StartSine(double amplitude_deg, double frequency_hz, int cycles) {
  if (interlock_open_) return RateTableRefusal::kInterlockOpen;
  if (!servo_on_) return RateTableRefusal::kServoOff;
  const double omega_radps = 2.0 * kPi * frequency_hz;
  const double peak_rate_dps = amplitude_deg * omega_radps;
  const double peak_accel_dps2 = amplitude_deg * omega_radps * omega_radps;
  if (!(amplitude_deg >= 0.0 && frequency_hz > 0.0 && cycles > 0) ||
      peak_rate_dps > params_.max_rate_dps || peak_accel_dps2 > params_.max_accel_dps2) {
    return RateTableRefusal::kBeyondLimit;
  }
  mode_ = Mode::kSine;
  commanded_rate_dps_ = 0.0;
  sine_start_deg_ = LeadAngle();
  sine_amplitude_deg_ = amplitude_deg;
  sine_frequency_hz_ = frequency_hz;
  sine_duration_s_ = cycles / frequency_hz;
  sine_elapsed_s_ = 0.0;
  ref_rate_dps_ = 0.0;
  return RateTableRefusal::kNone;
}

void RateTable::SetInterlockOpen(bool open) {
  if (open && !interlock_open_ && servo_on_) {
    // The drive brakes to rest at its limit and drops out (rate mode at 0, then coast).
    servo_on_ = false;
    braking_ = true;
    mode_ = Mode::kRate;
    ref_rate_dps_ = rate_smooth_dps_;
    commanded_rate_dps_ = 0.0;
  }
  interlock_open_ = open;
}

void RateTable::SetStalled(bool stalled) { stalled_ = stalled; }

double RateTable::platter_rate_dps() const {
  const double k = params_.rate_ripple_ratio;
  return measured_rate_dps() * (1.0 + k * std::cos(DegToRad(angle_smooth_deg_)));
}

double RateTable::platter_angle_deg() const {
  const double k = params_.rate_ripple_ratio;
  return Wrap360(angle_smooth_deg_ + RadToDeg(k * std::sin(DegToRad(angle_smooth_deg_))));
}

double RateTable::measured_angle_deg() const { return Wrap360(angle_smooth_deg_); }

RateTableStatus RateTable::status() const {
  RateTableStatus s;
  s.servo_on = servo_on_;
  s.interlock_open = interlock_open_;
  s.stalled = stalled_;
  const double rate_dps = measured_rate_dps();
  s.moving = std::fabs(rate_dps) > params_.at_rate_band_dps;
  s.at_rate = servo_on_ && mode_ == Mode::kRate && ref_rate_dps_ == commanded_rate_dps_ &&
              std::fabs(rate_dps - commanded_rate_dps_) <= params_.at_rate_band_dps;
  s.in_position = servo_on_ && mode_ == Mode::kPosition && ref_angle_deg_ == target_angle_deg_ &&
                  !s.moving &&
                  std::fabs(angle_smooth_deg_ - target_angle_deg_) <= params_.in_position_band_deg;
  return s;
}

}  // namespace adahrs::rig_sim
