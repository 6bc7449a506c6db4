// The Watlow Series F4 ramping controller as its Modbus client sees it: the register map, the
// static set point with its limits, and the profile engine (ramp time, ramp rate, soak, jump with
// repeat count, end; guaranteed-soak band). The chamber physics lives elsewhere
// (rig_sim/watlow_f4_device.h drives a ChamberAir with WorkingSetPointC()); this class only sees
// the process value it is given each control tick. Sources: shared/protocols.md §2.1–2.6 (register
// numbers DRV, exceptions 01/02/03 DOC, recipes DRV, guaranteed soak INF). Choices where the
// drivers are silent (INF): FC 16 writes register by register and stops at the first refusal; a
// profile starts ramping from the process value; a soak holds the set point it starts with; a jump
// with count N is taken N times; the running profile cannot be edited (03).
// Units: temperatures °C (register 901 reads 1), signed 16-bit with `decimals` implied decimals;
// times s; rates °C/min (register 4043 = rate × 10).
// Every register with its confidence, the profile engine: docs/rig/watlow-f4.md.
// Left out: channel 2 and cascade, autostart and wait-fors (→ 03), alarms, PID tuning, the
// real-time clock, non-volatile storage (register 25 accepted).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "hil/codecs/modbus_rtu.h"

namespace adahrs::rig_sim {

/// Controller settings (the F4's setup pages), validated by the device factory.
struct WatlowF4Settings {
  int decimals = 1;  ///< implied decimals of temperatures (register 606), 0 or 1
  double set_point_low_limit_c = -70.0;   ///< register 602
  double set_point_high_limit_c = 180.0;  ///< register 603
  double static_set_point_c = 25.0;       ///< register 300 at power-up
  double guaranteed_soak_band_c = 1.0;    ///< register 1205
};

class WatlowF4 {
 public:
  static constexpr int kProfiles = 40;     // §2.3 register 1218: "of 40"
  static constexpr int kTotalSteps = 256;  // §2.3 register 1219: "of 256 total"
  static constexpr uint16_t kStepBlockFirst = 4003;
  static constexpr uint16_t kStepBlockLast = 4062;

  /// Register 200 values (§2.3 DRV: 2 running, 3 holding; ChamberConnect treats 0/1 as constant).
  enum class Mode : uint16_t { kStatic = 0, kRunning = 2, kHolding = 3 };
  /// Step types, register 4003 (§2.4 DRV).
  enum StepType : uint16_t {
    kAutostart = 0,
    kRampTime = 1,
    kRampRate = 2,
    kSoak = 3,
    kJump = 4,
    kEnd = 5
  };
  /// End actions, register 4060 (§2.4 DRV).
  enum EndAction : uint16_t { kHold = 0, kControlOff = 1, kAllOff = 2, kIdle = 3 };

  explicit WatlowF4(const WatlowF4Settings& settings);

  /// Serves one decoded request (FC 03/06/16) and returns the reply (normal or exception).
  hil::modbus::Response Handle(const hil::modbus::Request& request);

  /// Advances the profile engine by `dt_s` with the measured process value `pv_c`.
  void Tick(double dt_s, double pv_c);
  /// The loop's output now, fractions 0...1 of the heating and the cooling capacity (registers
  /// 103 and 107 in hundredths of a percent).
  void SetOutputPower(double heat_fraction, double cool_fraction);

  /// The set point the loop controls to now: the profile's ramping set point (register 4122)
  /// while a profile runs or holds, else the static set point (300).
  double WorkingSetPointC() const;
  /// False after an end step with action "control off" or "all off" until a new set point or run.
  bool control_on() const { return control_on_; }
  Mode mode() const { return mode_; }
  /// Profile and step (1-based) being executed, 0 when no profile runs.
  int current_profile() const { return running_ ? profile_ + 1 : 0; }
  int current_step() const { return running_ ? step_ + 1 : 0; }

 private:
  struct Step {
    std::array<uint16_t, kStepBlockLast - kStepBlockFirst + 1> regs{};  // 4003..4062
    uint16_t jumps_done = 0;
    uint16_t Reg(uint16_t reg) const { return regs[reg - kStepBlockFirst]; }
  };
  struct Profile {
    bool exists = false;
    std::vector<Step> steps;
  };
  using Exception = std::optional<hil::modbus::ExceptionCode>;

  Exception Read(uint16_t reg, uint16_t& value) const;
  Exception Write(uint16_t reg, uint16_t value);
  Exception WriteStepRegister(uint16_t reg, uint16_t value);
  Exception EditAction(uint16_t action);
  Exception StartProfile();

  uint16_t ToReg(double c) const;
  double FromReg(uint16_t value) const;
  bool WithinLimits(double c) const;
  Step* SelectedStep();
  const Step* SelectedStep() const;
  int StepsUsed() const;

  // Profile engine.
  void EnterStep(int profile, int step);
  void FinishProfile(const Step* end_step);
  double StepRemainingS() const;

  WatlowF4Settings settings_;
  double static_set_point_c_;
  double pv_c_;
  uint16_t heat_power_ = 0;  // register 103, 0.01 %
  uint16_t cool_power_ = 0;  // register 107
  std::array<Profile, kProfiles> profiles_;
  std::array<uint16_t, 10 * kProfiles> names_;
  uint16_t selected_profile_ = 1;  // register 4000
  uint16_t selected_step_ = 1;     // register 4001

  Mode mode_ = Mode::kStatic;
  bool running_ = false;
  bool control_on_ = true;
  int profile_ = 0;  // 0-based index of the running profile
  int step_ = 0;     // 0-based index of the running step
  double step_elapsed_s_ = 0.0;
  double step_duration_s_ = 0.0;
  double ramp_start_c_ = 0.0;
  double ramp_target_c_ = 0.0;
  double profile_set_point_c_ = 0.0;
  double end_set_point_c_ = 0.0;
  bool guaranteed_soak_waiting_ = false;
  uint16_t last_jump_done_ = 0;     // register 4126
  uint16_t last_jump_profile_ = 0;  // register 4127
  uint16_t last_jump_step_ = 0;     // register 4128
};

}  // namespace adahrs::rig_sim
