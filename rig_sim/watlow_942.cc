#include "rig_sim/watlow_942.h"

#include <algorithm>
#include <cmath>

namespace adahrs::rig_sim {

using hil::Watlow942Command;
using hil::Watlow942Error;

namespace {

// `? MODE` values (p. 18): bit 1 run, bit 2 hold; 34 = off as rendered in the manual.
constexpr int kModeRunBits = 1;
constexpr int kModeHoldBits = 2;
constexpr int kModeOffBits = 34;

bool IsInteger(double value) { return value == std::floor(value); }
bool IntegerIn(double value, int lo, int hi) {
  return IsInteger(value) && value >= lo && value <= hi;
}

}  // namespace

Watlow942::Watlow942(const Watlow942Params& params)
    : params_(params),
      air_(params.air, params.initial_air_c),
      set_point_c_(params.initial_set_point_c) {
  jumps_left_.fill(-1);
}

std::optional<std::vector<std::string>> Watlow942::Handle(const hil::Watlow942Message& message) {
  if (message.command == Watlow942Command::kRead) return Read(message);
  Write(message);
  return std::nullopt;
}

std::string Watlow942::Number(double value) const {
  // Every value this controller holds fits in 7 characters at ≤ 2 decimals (|value| < 10^4).
  return hil::FormatWatlow942Number(value, params_.decimals).value_or("-9999");
}

double Watlow942::DurationS(const Step& step) {
  return step.hours * 3600.0 + step.minutes * 60.0 + step.seconds;
}

std::vector<std::string> Watlow942::StepFields(int number) const {
  const Step& s = steps_[static_cast<size_t>(number)];
  std::vector<std::string> fields{std::to_string(number), std::to_string(s.type)};
  auto add_int = [&](int v) { fields.push_back(std::to_string(v)); };
  switch (s.type) {
    case 1:
      fields.push_back(Number(s.sp_c));
      if (params_.profile_by_rate) {
        fields.push_back(Number(s.rate_c_per_min));
      } else {
        add_int(s.hours), add_int(s.minutes), add_int(s.seconds);
      }
      add_int(s.event1), add_int(s.event2);
      break;
    case 2:
      add_int(s.hours), add_int(s.minutes), add_int(s.seconds), add_int(s.event1),
          add_int(s.event2);
      break;
    case 3:
      add_int(s.jump_step), add_int(s.jump_count);
      break;
    default:
      add_int(s.end_action);
  }
  return fields;
}

std::optional<std::vector<std::string>> Watlow942::Read(const hil::Watlow942Message& m) {
  const std::string& mn = m.mnemonic;
  const Step& current = steps_[static_cast<size_t>(step_)];
  if (mn == "C1") return std::vector{Number(air_c())};
  if (mn == "CSP" || mn == "SP1") return std::vector{Number(set_point_c_)};
  if (mn == "ENSP") {
    return std::vector{Number(profile_active_ && current.type == 1 ? current.sp_c : set_point_c_)};
  }
  if (mn == "EJC") return std::vector{std::to_string(ejc_)};
  if (mn == "ERR") return std::vector<std::string>{"0"};
  if (mn == "ER2") {
    const int code = static_cast<int>(er2_);
    er2_ = Watlow942Error::kNone;  // cleared when read (p. 25)
    return std::vector{std::to_string(code)};
  }
  if (mn == "MDL")
    return std::vector<std::string>{"942", std::to_string(params_.software_revision)};
  if (mn == "MODE") {
    const int bits = mode_ == Mode::kRun    ? kModeRunBits
                     : mode_ == Mode::kHold ? kModeHoldBits
                                            : kModeOffBits;
    return std::vector{std::to_string(bits)};
  }
  if (mn == "MTR") return StepFields(step_);
  if (mn == "RL") return std::vector{Number(params_.range_low_c)};
  if (mn == "RH") return std::vector{Number(params_.range_high_c)};
  if (mn == "STP") {
    if (m.data.empty()) {
      er2_ = Watlow942Error::kIncompleteCommandLine;
      return std::nullopt;
    }
    if (m.data.size() > 1 || !IntegerIn(m.data[0], 1, kProfileSteps)) {
      er2_ = Watlow942Error::kInputOutOfLimit;
      return std::nullopt;
    }
    return StepFields(static_cast<int>(m.data[0]));
  }
  er2_ = (mn == "STRT" || mn == "HOLD" || mn == "RESU") ? Watlow942Error::kWriteOnly
                                                        : Watlow942Error::kParameterNotFound;
  return std::nullopt;
}

void Watlow942::Write(const hil::Watlow942Message& m) {
  const std::string& mn = m.mnemonic;
  const double value = m.data[0];
  const bool single = m.data.size() == 1;
  if (mn == "C1" || mn == "CSP" || mn == "ENSP" || mn == "EJC" || mn == "ERR" || mn == "ER2" ||
      mn == "MDL" || mn == "MODE" || mn == "MTR") {
    er2_ = Watlow942Error::kReadOnly;
  } else if (mn == "SP1") {
    if (mode_ == Mode::kRun) {
      er2_ = Watlow942Error::kInvalidInRunMode;
    } else if (!single || value < params_.range_low_c || value > params_.range_high_c) {
      er2_ = Watlow942Error::kInputOutOfLimit;
    } else {
      set_point_c_ = value;
    }
  } else if (mn == "RL" || mn == "RH") {
    const bool low = mn == "RL";
    const bool ok = single && (low ? value >= params_.air.min_c && value < params_.range_high_c
                                   : value <= params_.air.max_c && value > params_.range_low_c);
    if (mode_ == Mode::kRun) {
      er2_ = Watlow942Error::kInvalidInRunMode;
    } else if (!ok) {
      er2_ = Watlow942Error::kInputOutOfLimit;
    } else {
      (low ? params_.range_low_c : params_.range_high_c) = value;
    }
  } else if (mn == "STP") {
    if (mode_ == Mode::kRun) {
      er2_ = Watlow942Error::kInvalidInRunMode;  // steps are written in hold only (p. 22)
    } else {
      WriteStep(m.data);
    }
  } else if (mn == "STRT" || mn == "HOLD" || mn == "RESU") {
    if (!single || value != 1.0) {
      er2_ = Watlow942Error::kInputOutOfLimit;
    } else if (mn == "STRT") {
      if (mode_ == Mode::kRun) {
        er2_ = Watlow942Error::kRequestToRunInvalid;
      } else {
        Start(1);
      }
    } else if (mn == "HOLD") {
      if (mode_ == Mode::kHold) {
        er2_ = Watlow942Error::kRequestToHoldInvalid;
      } else {
        mode_ = Mode::kHold;
      }
    } else if (mode_ == Mode::kRun || !profile_active_) {
      er2_ = Watlow942Error::kRequestToRunInvalid;
    } else {
      mode_ = Mode::kRun;
    }
  } else {
    er2_ = Watlow942Error::kParameterNotFound;
  }
}

void Watlow942::WriteStep(const std::vector<double>& d) {
  // `= STP <step#> <type> <fields...>`, field layout of Table 8 (p. 22, protocols.md §3.6).
  if (d.size() < 2) {
    er2_ = Watlow942Error::kIncompleteCommandLine;
    return;
  }
  if (!IntegerIn(d[0], 1, kProfileSteps) || !IntegerIn(d[1], 0, 3)) {
    er2_ = Watlow942Error::kInputOutOfLimit;
    return;
  }
  const int number = static_cast<int>(d[0]);
  Step s;
  s.type = static_cast<int>(d[1]);
  const size_t fields_wanted = s.type == 1   ? (params_.profile_by_rate ? 4 : 6)
                               : s.type == 2 ? 5
                               : s.type == 3 ? 2
                                             : 1;
  if (d.size() - 2 != fields_wanted) {
    er2_ = d.size() - 2 < fields_wanted ? Watlow942Error::kIncompleteCommandLine
                                        : Watlow942Error::kTooManyCharacters;
    return;
  }
  const double* f = d.data() + 2;
  bool ok = true;
  auto time_fields = [&](const double* t) {
    ok = ok && IntegerIn(t[0], 0, 99) && IntegerIn(t[1], 0, 59) && IntegerIn(t[2], 0, 59);
    s.hours = static_cast<int>(t[0]), s.minutes = static_cast<int>(t[1]),
    s.seconds = static_cast<int>(t[2]);
  };
  auto events = [&](const double* e) {
    ok = ok && IntegerIn(e[0], 0, 1) && IntegerIn(e[1], 0, 1);
    s.event1 = static_cast<int>(e[0]), s.event2 = static_cast<int>(e[1]);
  };
  switch (s.type) {
    case 1:
      s.sp_c = f[0];
      ok = f[0] >= params_.range_low_c && f[0] <= params_.range_high_c;
      if (params_.profile_by_rate) {
        s.rate_c_per_min = f[1];
        ok = ok && f[1] > 0.0 && f[1] <= params_.max_ramp_rate_c_per_min;
        events(f + 2);
      } else {
        time_fields(f + 1);
        events(f + 4);
      }
      break;
    case 2:
      time_fields(f);
      events(f + 3);
      break;
    case 3:
      // A jump goes back to an earlier step, at most 100 times (EJC range, p. 18).
      ok = IntegerIn(f[0], 1, number - 1) && IntegerIn(f[1], 0, 100);
      s.jump_step = static_cast<int>(f[0]), s.jump_count = static_cast<int>(f[1]);
      break;
    default:
      ok = IntegerIn(f[0], 0, 1);
      s.end_action = static_cast<int>(f[0]);
  }
  if (!ok) {
    er2_ = Watlow942Error::kInputOutOfLimit;
    return;
  }
  steps_[static_cast<size_t>(number)] = s;
}

void Watlow942::Start(int step) {
  jumps_left_.fill(-1);
  ejc_ = 0;
  profile_active_ = true;
  mode_ = Mode::kRun;
  EnterStep(step);
}

void Watlow942::EnterStep(int step) {
  step_ = step;
  step_elapsed_s_ = 0.0;
  step_start_c_ = set_point_c_;
}

void Watlow942::AdvanceTo(double now_s) {
  // Tick k covers (k−1, k]·kTick_s; a tolerance of 1e-6 tick absorbs the rounding of now_s.
  const auto target_ticks = static_cast<int64_t>(std::floor(now_s / kTick_s + 1e-6));
  for (; ticks_ < target_ticks; ++ticks_) {
    if (mode_ == Mode::kRun) RunProfile(kTick_s);
    const bool controlling = mode_ != Mode::kOff && !cannot_reach_set_point_;
    air_.Step(controlling ? set_point_c_ : params_.ambient_c, kTick_s);
  }
}

void Watlow942::RunProfile(double dt_s) {
  double left_s = dt_s;
  // Zero-time steps (jump, end, a ramp already at its target) are taken within the same tick;
  // jump counts are bounded (≤ 100 per loop), so this loop ends.
  while (mode_ == Mode::kRun && (left_s > 0.0 || steps_[static_cast<size_t>(step_)].type == 3 ||
                                 steps_[static_cast<size_t>(step_)].type == 0)) {
    Step& s = steps_[static_cast<size_t>(step_)];
    const int next = step_ + 1;
    if (s.type == 1 && params_.profile_by_rate) {
      const double rate_c_per_s = s.rate_c_per_min / 60.0;
      const double needed_s = std::abs(s.sp_c - set_point_c_) / rate_c_per_s;
      if (needed_s <= left_s) {
        set_point_c_ = s.sp_c;
        left_s -= needed_s;
      } else {
        set_point_c_ += std::copysign(rate_c_per_s * left_s, s.sp_c - set_point_c_);
        left_s = 0.0;
        continue;
      }
    } else if (s.type == 1 || s.type == 2) {
      const double duration_s = DurationS(s);
      const double remaining_s = duration_s - step_elapsed_s_;
      if (remaining_s <= left_s) {
        if (s.type == 1) set_point_c_ = s.sp_c;
        left_s -= remaining_s;
      } else {
        step_elapsed_s_ += left_s;
        if (s.type == 1)
          set_point_c_ = step_start_c_ + (s.sp_c - step_start_c_) * step_elapsed_s_ / duration_s;
        left_s = 0.0;
        continue;
      }
    } else if (s.type == 3) {
      int& left = jumps_left_[static_cast<size_t>(step_)];
      if (left < 0) left = s.jump_count;
      if (left > 0) {
        --left;
        ejc_ = left;
        EnterStep(s.jump_step);
        continue;
      }
      left = -1;  // re-armed for the next pass through an enclosing loop
      ejc_ = 0;
    } else {
      mode_ = s.end_action == 1 ? Mode::kOff : Mode::kHold;
      profile_active_ = false;
      return;
    }
    if (next > kProfileSteps) {
      mode_ = Mode::kHold;
      profile_active_ = false;
      return;
    }
    EnterStep(next);
  }
}

}  // namespace adahrs::rig_sim
