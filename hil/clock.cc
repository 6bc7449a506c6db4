#include "hil/clock.h"

#include "hil/rig_clock.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>

namespace adahrs::hil {

std::chrono::milliseconds Clock::WallTimeout(double duration_s) const {
  const double wall_ms = duration_s / time_scale() * 1000.0;
  return std::chrono::milliseconds(std::max<long long>(1, static_cast<long long>(wall_ms)));
}

WallClock::WallClock() : start_(std::chrono::steady_clock::now()) {}

double WallClock::NowS() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void WallClock::SleepS(double duration_s) const {
  if (duration_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(duration_s));
}

ScaledClock::ScaledClock(double time_scale)
    : start_(std::chrono::steady_clock::now()), time_scale_(time_scale) {
  if (!(time_scale >= 0.01 && time_scale <= 1e6)) {
    throw std::invalid_argument("time scale " + std::to_string(time_scale) +
                                " outside [0.01, 1e6]");
  }
}

double ScaledClock::NowS() const {
  return time_scale_ *
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ScaledClock::SleepS(double duration_s) const {
  if (duration_s > 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(duration_s / time_scale_));
  }
}

ReplyDeadline::ReplyDeadline(const Clock& clock,
                             double timeout_s,
                             std::chrono::milliseconds wall_timeout)
    : clock_(clock), timeout_s_(timeout_s), wall_timeout_(wall_timeout) {
  Restart();
}

void ReplyDeadline::Restart() {
  wall_start_ = std::chrono::steady_clock::now();
  clock_deadline_s_ = clock_.NowS() + timeout_s_;
}

bool ReplyDeadline::Passed() const {
  const auto waited = std::chrono::steady_clock::now() - wall_start_;
  if (waited < wall_timeout_) return false;
  if (!clock_.may_pause() || waited >= kMaxReplyWall) return true;
  return clock_.NowS() >= clock_deadline_s_;
}

std::chrono::milliseconds ReplyDeadline::WaitLeft() const {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
      wall_start_ + wall_timeout_ - std::chrono::steady_clock::now());
  if (left.count() >= 1) return left;
  return clock_.may_pause() ? std::chrono::milliseconds(10) : std::chrono::milliseconds(1);
}

std::unique_ptr<Clock> MakeClock(double time_scale) {
  if (time_scale == 1.0) return std::make_unique<WallClock>();
  return std::make_unique<ScaledClock>(time_scale);
}

std::unique_ptr<Clock> MakeClock(double time_scale, const std::string& clock_file) {
  if (clock_file.empty()) return MakeClock(time_scale);
  return std::make_unique<RigClock>(clock_file);
}

}  // namespace adahrs::hil
