#include "rig_sim/watlow_f4.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace adahrs::rig_sim {
namespace {

using hil::modbus::ExceptionCode;

// Register numbers, shared/protocols.md §2.3–2.4.
constexpr uint16_t kRegModel = 0;  // 5270: '4' (52) and 'F' (70), DRV
constexpr uint16_t kModelF4 = 5270;
constexpr uint16_t kRegIdentLast = 5;  // serial number (1, 2), software (3, 4), date (5)
constexpr uint16_t kRegAlarm1Status = 102;
constexpr uint16_t kRegHeatPower = 103;
constexpr uint16_t kRegCoolPower = 107;
constexpr uint16_t kRegSensor = 600;
constexpr uint16_t kRegInputErrorLatch = 607;
constexpr uint16_t kRegSave = 25;
constexpr uint16_t kRegPv = 100;
constexpr uint16_t kRegInputError = 101;
constexpr uint16_t kRegMode = 200;
constexpr uint16_t kRegSetPoint = 300;
constexpr uint16_t kRegSpLowLimit = 602;
constexpr uint16_t kRegSpHighLimit = 603;
constexpr uint16_t kRegDecimals = 606;
constexpr uint16_t kRegProcessUnits = 608;
constexpr uint16_t kRegCelsius = 901;
constexpr uint16_t kRegSoakBand = 1205;
constexpr uint16_t kRegResume = 1209;
constexpr uint16_t kRegHold = 1210;
constexpr uint16_t kRegTerminate = 1217;
constexpr uint16_t kRegProfilesLeft = 1218;
constexpr uint16_t kRegStepsLeft = 1219;
constexpr uint16_t kRegNameFirst = 3500;
constexpr uint16_t kRegNameLast = 3500 + 10 * WatlowF4::kProfiles - 1;
constexpr uint16_t kRegProfile = 4000;
constexpr uint16_t kRegStep = 4001;
constexpr uint16_t kRegEditAction = 4002;
constexpr uint16_t kRegStepType = 4003;
constexpr uint16_t kRegHours = 4009;
constexpr uint16_t kRegMinutes = 4010;
constexpr uint16_t kRegSeconds = 4011;
constexpr uint16_t kRegEventFirst = 4030;
constexpr uint16_t kRegRampRate = 4043;
constexpr uint16_t kRegTarget = 4044;
constexpr uint16_t kRegPidSet = 4046;
constexpr uint16_t kRegGuaranteedSoak = 4048;
constexpr uint16_t kRegJumpProfile = 4050;
constexpr uint16_t kRegJumpStep = 4051;
constexpr uint16_t kRegJumpCount = 4052;
constexpr uint16_t kRegEndAction = 4060;
constexpr uint16_t kRegIdleSetPoint = 4061;
constexpr uint16_t kRegStatusFirst = 4100;
constexpr uint16_t kRegStatusLast = 4130;

// Values 4003 reads for a step that does not exist ("> 5 means the profile does not exist", §2.4).
constexpr uint16_t kNoSuchStep = 6;
// Edit actions, register 4002 (§2.4; 4 = delete step is INF).
constexpr uint16_t kCreateProfile = 1;
constexpr uint16_t kInsertStep = 2;
constexpr uint16_t kDeleteProfile = 3;
constexpr uint16_t kDeleteStep = 4;
constexpr uint16_t kRunProfile = 5;

// Writable step registers with their accepted raw range (signed registers are checked apart).
// Wait-for enables (4012, 4013–4016, 4021/4023/4025) accept only 0: the simulation has no digital
// or analog inputs that could ever satisfy a wait.
struct StepRegisterRange {
  uint16_t reg;
  int min;
  int max;
};
constexpr StepRegisterRange kStepRanges[] = {
    {4004, 0, 1},  {4005, 1, 12}, {4006, 1, 31}, {4007, 0, 9999}, {4008, 0, 7},
    {4009, 0, 99}, {4010, 0, 59}, {4011, 0, 59}, {4012, 0, 0},    {4013, 0, 0},
    {4014, 0, 0},  {4015, 0, 0},  {4016, 0, 0},  {4021, 0, 0},    {4023, 0, 0},
    {4025, 0, 0},  {4030, 0, 1},  {4031, 0, 1},  {4032, 0, 1},    {4033, 0, 1},
    {4034, 0, 1},  {4035, 0, 1},  {4036, 0, 1},  {4037, 0, 1},    {4043, 0, 32767},
    {4046, 0, 4},  {4048, 0, 1},  {4050, 0, 40}, {4051, 0, 256},  {4052, 0, 9999},
    {4060, 0, 3},
};

// A step whose remaining time is below this has ended: sums of 0.1 s ticks fall short of a whole
// duration by rounding (~1e-10 s over hours), which must not cost a whole extra tick.
constexpr double kStepEnd_s = 1e-6;

bool IsNameCharacter(uint16_t value) {
  return value == ' ' || (value >= 'A' && value <= 'Z') || (value >= '0' && value <= '9');
}

double StepDurationS(const auto& step) {
  return 3600.0 * step.Reg(kRegHours) + 60.0 * step.Reg(kRegMinutes) + step.Reg(kRegSeconds);
}

}  // namespace

WatlowF4::WatlowF4(const WatlowF4Settings& settings)
    : settings_(settings),
      static_set_point_c_(settings.static_set_point_c),
      pv_c_(settings.static_set_point_c) {
  names_.fill(' ');
}

uint16_t WatlowF4::ToReg(double c) const {
  const double scaled = std::round(c * std::pow(10.0, settings_.decimals));
  return static_cast<uint16_t>(static_cast<int16_t>(std::clamp(scaled, -32768.0, 32767.0)));
}

double WatlowF4::FromReg(uint16_t value) const {
  return static_cast<int16_t>(value) / std::pow(10.0, settings_.decimals);
}

bool WatlowF4::WithinLimits(double c) const {
  // Compared in register counts so that a limit read back and written as a set point is accepted.
  const int16_t value = static_cast<int16_t>(ToReg(c));
  return value >= static_cast<int16_t>(ToReg(settings_.set_point_low_limit_c)) &&
         value <= static_cast<int16_t>(ToReg(settings_.set_point_high_limit_c));
}

WatlowF4::Step* WatlowF4::SelectedStep() {
  Profile& profile = profiles_[selected_profile_ - 1];
  if (!profile.exists || selected_step_ > profile.steps.size()) return nullptr;
  return &profile.steps[selected_step_ - 1];
}

const WatlowF4::Step* WatlowF4::SelectedStep() const {
  return const_cast<WatlowF4*>(this)->SelectedStep();
}

int WatlowF4::StepsUsed() const {
  int used = 0;
  for (const Profile& profile : profiles_) used += static_cast<int>(profile.steps.size());
  return used;
}

hil::modbus::Response WatlowF4::Handle(const hil::modbus::Request& request) {
  hil::modbus::Response response;
  response.address = request.address;
  response.function = request.function;
  Exception error;
  switch (request.function) {
    case hil::modbus::kReadHoldingRegisters:
      if (request.start_register + request.count > 0x10000) {
        error = ExceptionCode::kIllegalDataAddress;
        break;
      }
      for (uint16_t i = 0; i < request.count && !error; ++i) {
        uint16_t value = 0;
        error = Read(static_cast<uint16_t>(request.start_register + i), value);
        response.values.push_back(value);
      }
      break;
    case hil::modbus::kWriteSingleRegister:
      error = Write(request.start_register, request.values.at(0));
      response.start_register = request.start_register;
      response.values = request.values;
      break;
    case hil::modbus::kWriteMultipleRegisters:
      if (request.start_register + request.values.size() > 0x10000) {
        error = ExceptionCode::kIllegalDataAddress;
        break;
      }
      for (size_t i = 0; i < request.values.size() && !error; ++i) {
        error = Write(static_cast<uint16_t>(request.start_register + i), request.values[i]);
      }
      response.start_register = request.start_register;
      response.count = static_cast<uint16_t>(request.values.size());
      break;
    default:
      error = ExceptionCode::kIllegalFunction;
  }
  if (error) {
    response.is_exception = true;
    response.exception = *error;
    response.values.clear();
  }
  return response;
}

void WatlowF4::SetOutputPower(double heat_fraction, double cool_fraction) {
  heat_power_ = static_cast<uint16_t>(std::lround(10000.0 * std::clamp(heat_fraction, 0.0, 1.0)));
  cool_power_ = static_cast<uint16_t>(std::lround(10000.0 * std::clamp(cool_fraction, 0.0, 1.0)));
}

WatlowF4::Exception WatlowF4::Read(uint16_t reg, uint16_t& value) const {
  value = 0;
  if (reg >= kRegNameFirst && reg <= kRegNameLast) {
    value = names_[reg - kRegNameFirst];
    return std::nullopt;
  }
  if (reg >= kStepBlockFirst && reg <= kStepBlockLast) {
    const Step* step = SelectedStep();
    if (step == nullptr) {
      if (reg == kRegStepType) value = kNoSuchStep;
    } else {
      value = step->Reg(reg);
    }
    return std::nullopt;
  }
  if (reg >= kRegStatusFirst && reg <= kRegStatusLast) {
    if (!running_) {
      if (reg == 4122) value = ToReg(WorkingSetPointC());
      return std::nullopt;
    }
    const Step& step = profiles_[profile_].steps[step_];
    const double remaining_s = std::max(0.0, std::ceil(StepRemainingS()));
    const int remaining = static_cast<int>(remaining_s);
    switch (reg) {
      case 4100:
        value = static_cast<uint16_t>(profile_ + 1);
        break;
      case 4101:
        value = static_cast<uint16_t>(step_ + 1);
        break;
      case 4102:
        value = step.Reg(kRegStepType);
        break;
      case 4103:
        value = guaranteed_soak_waiting_ ? 1 : 0;
        break;
      case 4119:
        value = static_cast<uint16_t>(remaining / 3600);
        break;
      case 4120:
        value = static_cast<uint16_t>(remaining / 60 % 60);
        break;
      case 4121:
        value = static_cast<uint16_t>(remaining % 60);
        break;
      case 4122:
        value = ToReg(profile_set_point_c_);
        break;
      case 4124:
        value = step.Reg(kRegPidSet);
        break;
      case 4126:
        value = last_jump_done_;
        break;
      case 4127:
        value = last_jump_profile_;
        break;
      case 4128:
        value = last_jump_step_;
        break;
      case 4129:
        value = ToReg(end_set_point_c_);
        break;
      default:
        if (reg >= 4111 && reg <= 4118) value = step.Reg(kRegEventFirst + (reg - 4111));
        break;
    }
    return std::nullopt;
  }
  if (reg <= kRegIdentLast) {
    value = reg == kRegModel ? kModelF4 : 0;
    return std::nullopt;
  }
  switch (reg) {
    case kRegAlarm1Status:
      return std::nullopt;
    case kRegHeatPower:
      value = heat_power_;
      return std::nullopt;
    case kRegCoolPower:
      value = cool_power_;
      return std::nullopt;
    case kRegSensor:
      return std::nullopt;
    case kRegInputErrorLatch:
      return std::nullopt;
    case kRegPv:
      value = ToReg(pv_c_);
      return std::nullopt;
    case kRegInputError:
      return std::nullopt;  // 0: no sensor error
    case kRegMode:
      value = static_cast<uint16_t>(mode_);
      return std::nullopt;
    case kRegSetPoint:
      value = ToReg(static_set_point_c_);
      return std::nullopt;
    case kRegSpLowLimit:
      value = ToReg(settings_.set_point_low_limit_c);
      return std::nullopt;
    case kRegSpHighLimit:
      value = ToReg(settings_.set_point_high_limit_c);
      return std::nullopt;
    case kRegDecimals:
      value = static_cast<uint16_t>(settings_.decimals);
      return std::nullopt;
    case kRegProcessUnits:
      return std::nullopt;  // 0: temperature
    case kRegCelsius:
      value = 1;
      return std::nullopt;
    case kRegSoakBand:
      value = ToReg(settings_.guaranteed_soak_band_c);
      return std::nullopt;
    case kRegProfilesLeft: {
      const auto existing = std::count_if(
          profiles_.begin(), profiles_.end(), [](const Profile& p) { return p.exists; });
      value = static_cast<uint16_t>(kProfiles - existing);
      return std::nullopt;
    }
    case kRegStepsLeft:
      value = static_cast<uint16_t>(kTotalSteps - StepsUsed());
      return std::nullopt;
    case kRegProfile:
      value = selected_profile_;
      return std::nullopt;
    case kRegStep:
      value = selected_step_;
      return std::nullopt;
    default:
      return ExceptionCode::kIllegalDataAddress;
  }
}

WatlowF4::Exception WatlowF4::Write(uint16_t reg, uint16_t value) {
  if (reg >= kRegNameFirst && reg <= kRegNameLast) {
    if (!IsNameCharacter(value)) return ExceptionCode::kIllegalDataValue;
    names_[reg - kRegNameFirst] = value;
    return std::nullopt;
  }
  if (reg >= kStepBlockFirst && reg <= kStepBlockLast) return WriteStepRegister(reg, value);
  const double value_c = FromReg(value);
  switch (reg) {
    case kRegSave:
      return value == 0 ? Exception() : ExceptionCode::kIllegalDataValue;
    case kRegSetPoint:
      if (!WithinLimits(value_c)) return ExceptionCode::kIllegalDataValue;
      static_set_point_c_ = value_c;
      control_on_ = true;
      return std::nullopt;
    case kRegSpLowLimit:
      // A limit that would leave the present static set point outside is refused, not clamped.
      if (value_c > settings_.set_point_high_limit_c || value_c > static_set_point_c_) {
        return ExceptionCode::kIllegalDataValue;
      }
      settings_.set_point_low_limit_c = value_c;
      return std::nullopt;
    case kRegSpHighLimit:
      if (value_c < settings_.set_point_low_limit_c || value_c < static_set_point_c_) {
        return ExceptionCode::kIllegalDataValue;
      }
      settings_.set_point_high_limit_c = value_c;
      return std::nullopt;
    case kRegSoakBand:
      if (static_cast<int16_t>(value) < 0) return ExceptionCode::kIllegalDataValue;
      settings_.guaranteed_soak_band_c = value_c;
      return std::nullopt;
    case kRegResume:
      if (value != 1 || !running_) return ExceptionCode::kIllegalDataValue;
      mode_ = Mode::kRunning;
      return std::nullopt;
    case kRegHold:
      if (value != 1 || !running_) return ExceptionCode::kIllegalDataValue;
      mode_ = Mode::kHolding;
      return std::nullopt;
    case kRegTerminate:
      if (value != 1) return ExceptionCode::kIllegalDataValue;
      running_ = false;
      mode_ = Mode::kStatic;
      control_on_ = true;
      guaranteed_soak_waiting_ = false;
      return std::nullopt;
    case kRegProfile:
      if (value < 1 || value > kProfiles) return ExceptionCode::kIllegalDataValue;
      selected_profile_ = value;
      return std::nullopt;
    case kRegStep:
      if (value < 1 || value > kTotalSteps) return ExceptionCode::kIllegalDataValue;
      selected_step_ = value;
      return std::nullopt;
    case kRegEditAction:
      return EditAction(value);
    default:
      // Read-only (PV, mode, status, …) or unmapped: 02 either way (Watlow convention, §2.1 DOC).
      return ExceptionCode::kIllegalDataAddress;
  }
}

WatlowF4::Exception WatlowF4::WriteStepRegister(uint16_t reg, uint16_t value) {
  const auto* range = std::find_if(std::begin(kStepRanges),
                                   std::end(kStepRanges),
                                   [reg](const StepRegisterRange& r) { return r.reg == reg; });
  const bool is_set_point = reg == kRegTarget || reg == kRegIdleSetPoint;
  const bool is_analog_value = reg == 4022 || reg == 4024 || reg == 4026;
  if (reg != kRegStepType && range == std::end(kStepRanges) && !is_set_point && !is_analog_value) {
    return ExceptionCode::kIllegalDataAddress;  // gaps and channel-2 registers (F4S)
  }
  Step* step = SelectedStep();
  if (step == nullptr) return ExceptionCode::kIllegalDataValue;
  if (running_ && selected_profile_ == profile_ + 1) return ExceptionCode::kIllegalDataValue;
  if (reg == kRegStepType) {
    if (value < kRampTime || value > kEnd) return ExceptionCode::kIllegalDataValue;
  } else if (is_set_point) {
    if (!WithinLimits(FromReg(value))) return ExceptionCode::kIllegalDataValue;
  } else if (range != std::end(kStepRanges)) {
    if (value < range->min || value > range->max) return ExceptionCode::kIllegalDataValue;
  }
  step->regs[reg - kStepBlockFirst] = value;
  return std::nullopt;
}

WatlowF4::Exception WatlowF4::EditAction(uint16_t action) {
  Profile& profile = profiles_[selected_profile_ - 1];
  const bool profile_running = running_ && selected_profile_ == profile_ + 1;
  switch (action) {
    case kCreateProfile: {
      auto free = std::find_if(
          profiles_.begin(), profiles_.end(), [](const Profile& p) { return !p.exists; });
      if (free == profiles_.end() || StepsUsed() >= kTotalSteps) {
        return ExceptionCode::kIllegalDataValue;
      }
      free->exists = true;
      free->steps.assign(1, Step{});
      free->steps[0].regs[0] = kEnd;  // a new profile holds one end step (§2.5 DRV)
      selected_profile_ = static_cast<uint16_t>(free - profiles_.begin() + 1);
      selected_step_ = 1;
      return std::nullopt;
    }
    case kInsertStep:
      if (!profile.exists || profile_running || selected_step_ > profile.steps.size() ||
          StepsUsed() >= kTotalSteps) {
        return ExceptionCode::kIllegalDataValue;
      }
      profile.steps.insert(profile.steps.begin() + (selected_step_ - 1), Step{});
      profile.steps[selected_step_ - 1].regs[0] = kSoak;  // a zero-length soak until edited
      return std::nullopt;
    case kDeleteProfile:
      if (!profile.exists || profile_running) return ExceptionCode::kIllegalDataValue;
      profile = Profile{};
      return std::nullopt;
    case kDeleteStep:
      if (!profile.exists || profile_running || selected_step_ > profile.steps.size()) {
        return ExceptionCode::kIllegalDataValue;
      }
      profile.steps.erase(profile.steps.begin() + (selected_step_ - 1));
      return std::nullopt;
    case kRunProfile:
      return StartProfile();
    default:
      return ExceptionCode::kIllegalDataValue;
  }
}

WatlowF4::Exception WatlowF4::StartProfile() {
  if (running_) return ExceptionCode::kIllegalDataValue;
  const Profile& first = profiles_[selected_profile_ - 1];
  if (!first.exists || selected_step_ > first.steps.size()) {
    return ExceptionCode::kIllegalDataValue;
  }
  // Check every profile the run can reach: ramp rates must be positive and jumps must land on
  // an existing step; otherwise the run is refused before anything moves.
  std::set<int> to_check{selected_profile_ - 1};
  std::set<int> checked;
  while (!to_check.empty()) {
    const int index = *to_check.begin();
    to_check.erase(to_check.begin());
    if (!checked.insert(index).second) continue;
    for (const Step& step : profiles_[index].steps) {
      const uint16_t type = step.Reg(kRegStepType);
      if (type == kRampRate && step.Reg(kRegRampRate) == 0) return ExceptionCode::kIllegalDataValue;
      if (type != kJump) continue;
      const int jump_profile = step.Reg(kRegJumpProfile);
      const int jump_step = step.Reg(kRegJumpStep);
      if (jump_profile < 1 || !profiles_[jump_profile - 1].exists || jump_step < 1 ||
          jump_step > static_cast<int>(profiles_[jump_profile - 1].steps.size())) {
        return ExceptionCode::kIllegalDataValue;
      }
      to_check.insert(jump_profile - 1);
    }
  }
  for (Profile& profile : profiles_) {
    for (Step& step : profile.steps) step.jumps_done = 0;
  }
  running_ = true;
  mode_ = Mode::kRunning;
  control_on_ = true;
  last_jump_done_ = last_jump_profile_ = last_jump_step_ = 0;
  profile_set_point_c_ = pv_c_;  // a profile ramps from the process value (INF)
  end_set_point_c_ = 0.0;
  EnterStep(selected_profile_ - 1, selected_step_ - 1);
  return std::nullopt;
}

void WatlowF4::EnterStep(int profile, int step) {
  // Zero-length steps and jumps chain within one call; the bound only stops a pathological jump
  // web from spinning (each pass through a jump step consumes one of its finite repeats).
  for (int chained = 0; chained < 4 * kTotalSteps; ++chained) {
    const std::vector<Step>& steps = profiles_[profile].steps;
    if (step >= static_cast<int>(steps.size())) {
      FinishProfile(nullptr);
      return;
    }
    profile_ = profile;
    step_ = step;
    step_elapsed_s_ = 0.0;
    const Step& current = steps[step];
    const double target_c = FromReg(current.Reg(kRegTarget));
    switch (current.Reg(kRegStepType)) {
      case kRampTime:
        ramp_start_c_ = profile_set_point_c_;
        ramp_target_c_ = target_c;
        step_duration_s_ = StepDurationS(current);
        break;
      case kRampRate: {
        ramp_start_c_ = profile_set_point_c_;
        ramp_target_c_ = target_c;
        // 4043 = rate × 10 in °C per minute (§2.2 DRV).
        const double rate_c_per_s = current.Reg(kRegRampRate) / 10.0 / 60.0;
        step_duration_s_ = std::abs(target_c - ramp_start_c_) / rate_c_per_s;
        break;
      }
      case kSoak:
        ramp_start_c_ = ramp_target_c_ = profile_set_point_c_;
        step_duration_s_ = StepDurationS(current);
        break;
      case kJump: {
        Step& jump = profiles_[profile].steps[step];
        last_jump_profile_ = jump.Reg(kRegJumpProfile);
        last_jump_step_ = jump.Reg(kRegJumpStep);
        if (jump.jumps_done < jump.Reg(kRegJumpCount)) {
          ++jump.jumps_done;
          last_jump_done_ = jump.jumps_done;
          profile = jump.Reg(kRegJumpProfile) - 1;
          step = jump.Reg(kRegJumpStep) - 1;
        } else {
          jump.jumps_done = 0;  // an enclosing loop runs this one again in full
          ++step;
        }
        continue;
      }
      default:  // kEnd
        FinishProfile(&current);
        return;
    }
    if (step_duration_s_ > 0.0) return;
    profile_set_point_c_ = ramp_target_c_;
    ++step;
  }
}

void WatlowF4::FinishProfile(const Step* end_step) {
  running_ = false;
  mode_ = Mode::kStatic;
  guaranteed_soak_waiting_ = false;
  const uint16_t action = end_step != nullptr ? end_step->Reg(kRegEndAction) : uint16_t{kHold};
  end_set_point_c_ = profile_set_point_c_;
  switch (action) {
    case kIdle:
      end_set_point_c_ = FromReg(end_step->Reg(kRegIdleSetPoint));
      break;
    case kControlOff:
    case kAllOff:
      control_on_ = false;
      break;
    default:  // kHold
      break;
  }
  // After the profile the controller is in static mode at the end set point (INF).
  static_set_point_c_ = end_set_point_c_;
}

double WatlowF4::StepRemainingS() const { return step_duration_s_ - step_elapsed_s_; }

void WatlowF4::Tick(double dt_s, double pv_c) {
  pv_c_ = pv_c;
  double left_s = dt_s;
  while (running_ && mode_ == Mode::kRunning && left_s > 0.0) {
    const Step& step = profiles_[profile_].steps[step_];
    // Guaranteed soak: the step's clock (and a ramp's set point) stops while PV is out of band.
    guaranteed_soak_waiting_ =
        step.Reg(kRegGuaranteedSoak) == 1 &&
        std::abs(pv_c - profile_set_point_c_) > settings_.guaranteed_soak_band_c;
    if (guaranteed_soak_waiting_) return;
    const double advance_s = std::min(left_s, StepRemainingS());
    step_elapsed_s_ += advance_s;
    left_s -= advance_s;
    if (StepRemainingS() <= kStepEnd_s) {
      profile_set_point_c_ = ramp_target_c_;
      EnterStep(profile_, step_ + 1);
    } else {
      profile_set_point_c_ =
          ramp_start_c_ + (ramp_target_c_ - ramp_start_c_) * step_elapsed_s_ / step_duration_s_;
    }
  }
}

double WatlowF4::WorkingSetPointC() const {
  return running_ ? profile_set_point_c_ : static_set_point_c_;
}

}  // namespace adahrs::rig_sim
