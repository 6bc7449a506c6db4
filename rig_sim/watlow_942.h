// The virtual Watlow Series 942 ramping controller on the ADS bench chamber: the parameters a host
// reads and writes over the ASCII protocol (shared/protocols.md §3, DOC: 942 Data Communications
// manual pp. 18-25), the 24-step profile engine (pp. 21-23) and the chamber air it controls
// (rig_sim/chamber_air.h). Protocol bytes are handled by Watlow942Device; this class sees decoded
// messages only. Modes 1 run, 2 hold (power-up), 34 off; step types 1 set point, 2 soak, 3 jump
// loop, 0 end. Writes beyond a limit are refused with ER2 25, never clamped; the other refusals
// carry ER2 30, 31, 32 (p. 23, p. 18). Time advances in fixed 10 ms ticks from t = 0, so the state
// at any time is the same whatever granularity AdvanceTo is called with.
// Units: temperatures in °C (`_c`), ramp rates in °C/min, times in s; simulated time `now_s`.
// Parameters, step fields, error codes and physics: docs/rig/watlow-942.md.
// Left out: events drive nothing, no guaranteed-soak band, alarms, the set-up menus beyond rL/rH,
// calibration mode, the ER2 communication codes 1, 3-8 (a pty has no framing or parity errors).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hil/codecs/watlow942_codec.h"
#include "rig_sim/chamber_air.h"

namespace adahrs::rig_sim {

struct Watlow942Params {
  ChamberAirParams air;
  double initial_air_c = 25.0;
  double ambient_c = 25.0;  ///< where the air drifts with control off or failed
  double initial_set_point_c = 25.0;
  double range_low_c = -50.0;   ///< rL: lowest set point accepted
  double range_high_c = 100.0;  ///< rH: highest set point accepted
  double max_ramp_rate_c_per_min = 30.0;
  bool profile_by_rate = true;  ///< PtYP = rAtE (true) or tI (false)
  int decimals = 1;             ///< decimal places in replies (the 942's dEC setting)
  int software_revision = 1;    ///< the X of the `? MDL` reply `942 X`
};

class Watlow942 {
 public:
  static constexpr int kProfileSteps = 24;  // p. 21
  static constexpr double kTick_s = 0.01;
  enum class Mode { kRun, kHold, kOff };

  explicit Watlow942(const Watlow942Params& params);

  /// Applies one decoded message at the current time. Returns the reply fields of a `?` that
  /// succeeded; nullopt for a `=` or when the message was refused (the reason latched in ER2).
  std::optional<std::vector<std::string>> Handle(const hil::Watlow942Message& message);
  /// Latches a framing/decoding error in ER2 (the last error wins, as one register).
  void LatchError(hil::Watlow942Error error) { er2_ = error; }

  /// Advances the profile and the chamber air in 10 ms ticks up to `now_s`.
  void AdvanceTo(double now_s);

  /// Physical fault: the chamber cannot heat or cool (air drifts to ambient whatever the SP).
  void SetCannotReachSetPoint(bool on) { cannot_reach_set_point_ = on; }

  double air_c() const { return air_.air_c(); }
  double set_point_c() const { return set_point_c_; }
  Mode mode() const { return mode_; }
  int current_step() const { return step_; }

 private:
  struct Step {
    int type = 0;  // 0 end, 1 set point, 2 soak, 3 jump loop
    double sp_c = 0.0;
    double rate_c_per_min = 0.0;
    int hours = 0, minutes = 0, seconds = 0;
    int event1 = 0, event2 = 0;
    int jump_step = 0, jump_count = 0;
    int end_action = 0;  // 0 hold, 1 off
  };

  std::optional<std::vector<std::string>> Read(const hil::Watlow942Message& message);
  void Write(const hil::Watlow942Message& message);
  void WriteStep(const std::vector<double>& data);
  std::vector<std::string> StepFields(int number) const;
  std::string Number(double value) const;
  void Start(int step);
  void EnterStep(int step);
  void RunProfile(double dt_s);
  static double DurationS(const Step& step);

  Watlow942Params params_;
  ChamberAir air_;
  std::array<Step, kProfileSteps + 1> steps_{};  // 1-based
  Mode mode_ = Mode::kHold;
  double set_point_c_;
  bool profile_active_ = false;
  int step_ = 1;
  double step_elapsed_s_ = 0.0;
  double step_start_c_ = 0.0;
  std::array<int, kProfileSteps + 1> jumps_left_{};  // -1: loop not armed
  int ejc_ = 0;
  hil::Watlow942Error er2_ = hil::Watlow942Error::kNone;
  int64_t ticks_ = 0;
  bool cannot_reach_set_point_ = false;
};

}  // namespace adahrs::rig_sim
