#include "calib/sequence/execution_plan.h"

#include <cmath>

#include <fmt/format.h>

#include "calib/sequence/validation.h"
#include "common/overloaded.h"

namespace adahrs::calib {

using common::Overloaded;

namespace {

constexpr double kSecondsPerMinute = 60.0;

// Appends actions of one step while tracking the rig state the estimates depend on.
class Planner {
 public:
  Planner(const SequenceLimits& limits, const PlanTiming& timing, ExecutionPlan& plan)
      : limits_(limits),
        timing_(timing),
        plan_(plan),
        chamber_c_(timing.initial_chamber_c),
        alt_ft_(timing.initial_alt_ft),
        cas_kt_(timing.initial_cas_kt) {}

  void BeginStep(size_t step, uint8_t tag) {
    step_ = step;
    tag_ = tag;
  }

  void Add(Action action, double estimate_s) {
    plan_.actions.push_back({step_, tag_, std::move(action), estimate_s});
    plan_.duration_estimate_s += estimate_s;
  }

  void Mount(int orientation) {
    if (orientation == mounted_) return;
    Add(MountOrientation{orientation}, timing_.operator_prompt_s);
    mounted_ = orientation;
  }

  void Acquire(int64_t packets) {
    Add(AcquirePackets{packets}, static_cast<double>(packets) / limits_.packet_rate_hz);
  }

  void CheckGyro(int orientation, double accel_dps2) {
    // Up to the jog rate, sample, and back down.
    const double jog_dps = limits_.interlock_jog_rate_dps;
    Add(CheckGyroAxis{orientation, jog_dps},
        2.0 * jog_dps / accel_dps2 + timing_.table_settle_s + timing_.interlock_sample_s);
  }

  void TableRate(double rate_dps, double accel_dps2) {
    // A command returns at once; the wait that follows carries the motion's time (the executor
    // bounds each wait by its estimate).
    Add(SetTableRate{rate_dps, accel_dps2}, 0.0);
    Add(WaitTableAtRate{rate_dps},
        std::abs(rate_dps - table_dps_) / accel_dps2 + timing_.table_settle_s);
    table_dps_ = rate_dps;
  }

  void Stop(double accel_dps2) {
    Add(StopTable{accel_dps2}, std::abs(table_dps_) / accel_dps2);
    table_dps_ = 0.0;
  }

  void Chamber(const TargetTemperatureStep& s) {
    Add(SetChamberSetPoint{s.target_c}, 0.0);
    const double rate_c_per_min =
        s.target_c > chamber_c_
            ? timing_.chamber_heat_c_per_min.value_or(timing_.chamber_ramp_c_per_min)
            : timing_.chamber_cool_c_per_min.value_or(timing_.chamber_ramp_c_per_min);
    Add(WaitChamberSoak{s.target_c, s.band_c, s.soak_s},
        std::abs(s.target_c - chamber_c_) / rate_c_per_min * kSecondsPerMinute + s.soak_s);
    chamber_c_ = s.target_c;
  }

  void Profile(const ThermalProfileStep& s) {
    Add(DownloadProfile{s}, timing_.profile_download_s);
    Add(RunProfileLogging{s.profile_name}, ProfileDurationS(s, chamber_c_));
    chamber_c_ = ProfileEndSetPointC(s, chamber_c_);
  }

  void Altitude(const AltitudeStep& s) {
    Add(SetAltitude{s.alt_ft, s.rate_ft_per_min}, 0.0);
    Add(WaitAdtsStable{},
        std::abs(s.alt_ft - alt_ft_) / s.rate_ft_per_min * kSecondsPerMinute +
            timing_.adts_stable_s);
    alt_ft_ = s.alt_ft;
  }

  void Airspeed(const AirspeedStep& s) {
    Add(SetAirspeed{s.cas_kt, s.rate_kt_per_min}, 0.0);
    Add(WaitAdtsStable{},
        std::abs(s.cas_kt - cas_kt_) / s.rate_kt_per_min * kSecondsPerMinute +
            timing_.adts_stable_s);
    cas_kt_ = s.cas_kt;
  }

 private:
  static double ProfileEndSetPointC(const ThermalProfileStep& s, double start_c) {
    double set_point_c = start_c;
    for (const F4ProfileStep& step : s.steps) {
      if (const auto* r = std::get_if<F4RampTime>(&step)) set_point_c = r->target_c;
      if (const auto* r = std::get_if<F4RampRate>(&step)) set_point_c = r->target_c;
      if (const auto* e = std::get_if<F4End>(&step); e && e->action == F4EndAction::kIdle) {
        set_point_c = e->idle_c;
      }
    }
    return set_point_c;
  }

  const SequenceLimits& limits_;
  const PlanTiming& timing_;
  ExecutionPlan& plan_;
  size_t step_ = 0;
  uint8_t tag_ = 0;
  int mounted_ = 0;
  double table_dps_ = 0.0;
  double chamber_c_;
  double alt_ft_;
  double cas_kt_;
};

}  // namespace

double ProfileDurationS(const ThermalProfileStep& profile, double start_c) {
  // Walks the profile as the controller runs it. Each jump keeps the number of times it has been
  // taken; once taken `count` times it resets (so an enclosing loop runs it again in full) and
  // the walk goes on with the next step. Validation guarantees backward jumps with count ≥ 1, so
  // the walk ends.
  const auto& steps = profile.steps;
  std::vector<int> jumps_done(steps.size(), 0);
  double set_point_c = start_c;
  double total_s = 0.0;
  size_t i = 0;
  while (i < steps.size()) {
    const F4ProfileStep& step = steps[i];
    if (const auto* r = std::get_if<F4RampTime>(&step)) {
      total_s += r->duration_s;
      set_point_c = r->target_c;
    } else if (const auto* r = std::get_if<F4RampRate>(&step)) {
      total_s += std::abs(r->target_c - set_point_c) / r->rate_c_per_min * kSecondsPerMinute;
      set_point_c = r->target_c;
    } else if (const auto* s = std::get_if<F4Soak>(&step)) {
      total_s += s->duration_s;
    } else if (const auto* j = std::get_if<F4Jump>(&step)) {
      if (jumps_done[i] < j->count) {
        ++jumps_done[i];
        i = static_cast<size_t>(j->to_step - 1);
        continue;
      }
      jumps_done[i] = 0;
    } else {
      break;  // end step
    }
    ++i;
  }
  return total_s;
}

ExecutionPlan ExpandSequence(const Sequence& sequence,
                             const SequenceLimits& limits,
                             const PlanTiming& timing) {
  std::vector<SequenceProblem> problems = ValidateSequence(sequence, limits);
  if (!problems.empty()) throw SequenceError("sequence " + sequence.name, std::move(problems));
  const std::vector<uint8_t> tags = EffectiveTags(sequence);
  ExecutionPlan plan;
  Planner planner(limits, timing, plan);
  for (size_t i = 0; i < sequence.steps.size(); ++i) {
    planner.BeginStep(i, tags[i]);
    std::visit(Overloaded{
                   [&](const AccelStep& s) {
                     planner.Mount(s.orientation);
                     planner.Add(CheckGravity{s.orientation}, timing.interlock_sample_s);
                     planner.Acquire(s.packets);
                   },
                   [&](const GyroStep& s) {
                     planner.Mount(s.orientation);
                     planner.CheckGyro(s.orientation, s.table_accel_dps2);
                     for (double rate_dps : GyroRates_dps(s)) {
                       planner.TableRate(rate_dps, s.table_accel_dps2);
                       planner.Acquire(s.packets);
                     }
                     planner.Stop(s.table_accel_dps2);
                   },
                   [&](const TargetTemperatureStep& s) { planner.Chamber(s); },
                   [&](const CrossAxisStep& s) {
                     for (int orientation : kCrossAxisOrientations) {
                       planner.Mount(orientation);
                       planner.Add(CheckGravity{orientation}, timing.interlock_sample_s);
                       planner.Acquire(s.packets);
                       planner.CheckGyro(orientation, s.table_accel_dps2);
                       planner.TableRate(s.rate_dps, s.table_accel_dps2);
                       planner.Acquire(s.packets);
                       planner.Stop(s.table_accel_dps2);
                     }
                   },
                   [&](const ThermalProfileStep& s) { planner.Profile(s); },
                   [&](const AltitudeStep& s) { planner.Altitude(s); },
                   [&](const AirspeedStep& s) { planner.Airspeed(s); },
                   [&](const LogStep& s) {
                     if (s.packets) {
                       planner.Acquire(*s.packets);
                     } else {
                       planner.Add(LogForDuration{*s.duration_s}, *s.duration_s);
                     }
                   },
                   [&](const PromptStep& s) {
                     planner.Add(PromptOperator{s.text}, timing.operator_prompt_s);
                   },
               },
               sequence.steps[i].body);
  }
  return plan;
}

std::string Describe(const Action& action) {
  return std::visit(
      Overloaded{
          [](const PromptOperator& a) { return fmt::format("prompt operator: \"{}\"", a.text); },
          [](const MountOrientation& a) {
            return fmt::format("mount batch in orientation {}", a.orientation);
          },
          [](const CheckGravity& a) {
            return fmt::format("interlock: check gravity for orientation {}", a.orientation);
          },
          [](const CheckGyroAxis& a) {
            return fmt::format("interlock: jog {:g} deg/s, check gyro axis for orientation {}",
                               a.jog_rate_dps,
                               a.orientation);
          },
          [](const SetTableRate& a) {
            return fmt::format(
                "set table rate {:g} deg/s (accel {:g} deg/s^2)", a.rate_dps, a.accel_dps2);
          },
          [](const WaitTableAtRate& a) {
            return fmt::format("wait table at {:g} deg/s", a.rate_dps);
          },
          [](const StopTable&) { return std::string("stop table"); },
          [](const SetChamberSetPoint& a) {
            return fmt::format("set chamber set point {:g} degC", a.temp_c);
          },
          [](const WaitChamberSoak& a) {
            return fmt::format(
                "wait chamber within {:g} ± {:g} degC, soak {:g} s", a.temp_c, a.band_c, a.soak_s);
          },
          [](const DownloadProfile& a) {
            return fmt::format("download chamber profile \"{}\" ({} steps)",
                               a.profile.profile_name,
                               a.profile.steps.size());
          },
          [](const RunProfileLogging& a) {
            return fmt::format("run chamber profile \"{}\", logging until its end", a.profile_name);
          },
          [](const SetAltitude& a) {
            return fmt::format(
                "set ADTS altitude {:g} ft at {:g} ft/min", a.alt_ft, a.rate_ft_per_min);
          },
          [](const SetAirspeed& a) {
            return fmt::format(
                "set ADTS airspeed {:g} kt at {:g} kt/min", a.cas_kt, a.rate_kt_per_min);
          },
          [](const WaitAdtsStable&) { return std::string("wait ADTS stable"); },
          [](const AcquirePackets& a) { return fmt::format("acquire {} packets", a.packets); },
          [](const LogForDuration& a) { return fmt::format("log for {:g} s", a.duration_s); },
      },
      action);
}

}  // namespace adahrs::calib
