#include "calib/executor/executor.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "calib/executor/chamber_eta.h"
#include "calib/executor/interlocks.h"
#include "common/overloaded.h"

namespace adahrs::calib {

using common::Overloaded;

namespace {

// Waits for every unit's request (one per logger, in order); throws a RunError naming every
// unit whose request failed, after all have finished.
void WaitAll(std::vector<std::future<void>> requests,
             const std::vector<UnitLogger*>& loggers,
             const std::string& where) {
  std::string failures;
  for (size_t u = 0; u < requests.size(); ++u) {
    try {
      requests[u].get();
    } catch (const std::exception& e) {
      failures += fmt::format("{}unit {} ({}): {}",
                              failures.empty() ? "" : "; ",
                              loggers[u]->role(),
                              loggers[u]->serial(),
                              e.what());
    }
  }
  if (!failures.empty()) throw RunError(where + ": " + failures);
}

std::string JoinRoles(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace

Executor::Executor(const Sequence& sequence,
                   const ExecutionPlan& plan,
                   BatchInstruments instruments,
                   std::vector<UnitLogger*> loggers,
                   const hil::Clock& clock,
                   RunAnnotations& annotations,
                   SharedRecording& recording,
                   Journal& journal,
                   RunMeta& meta,
                   ProgressSink& progress,
                   const std::atomic<bool>& stop,
                   ExecutorOptions options)
    : sequence_(sequence),
      plan_(plan),
      instruments_(instruments),
      loggers_(std::move(loggers)),
      clock_(clock),
      annotations_(annotations),
      recording_(recording),
      journal_(journal),
      meta_(meta),
      progress_(progress),
      stop_(stop),
      options_(options) {
  for (const UnitLogger* l : loggers_) roles_.push_back(l->role());
  gravity_references_.resize(loggers_.size());
}

void Executor::Run(size_t first_step, std::optional<double> resumed_from_s) {
  size_t first_action = 0;
  while (first_action < plan_.actions.size() && plan_.actions[first_action].step < first_step) {
    ++first_action;
  }
  current_action_ = first_action;
  try {
    EndAcquisitions();
    SafeStart();
    if (resumed_from_s) {
      const double now_s = clock_.NowS();
      meta_.AddRejectedInterval(first_step, *resumed_from_s, now_s, "repeated partial step");
      journal_.Append(StepRepeated{now_s, first_step, *resumed_from_s});
      journal_.Sync();
      progress_.Note(fmt::format("repeating step {} (its rows since t = {:.2f} s are rejected)",
                                 first_step,
                                 *resumed_from_s));
    }
    if (first_action > 0) RestoreState(first_action);
    RunActions(first_action);
  } catch (const RunInterrupted& e) {
    journal_.Append(RunStopped{clock_.NowS(), current_action_, e.what(), false});
    MakeSafe();
    meta_.SetStatus(kStatusInterrupted);
    throw;
  } catch (const std::exception& e) {
    const std::string message =
        dynamic_cast<const RunError*>(&e) ? std::string(e.what()) : Where() + ": " + e.what();
    journal_.Append(RunStopped{clock_.NowS(), current_action_, message, true});
    MakeSafe();
    meta_.SetStatus(kStatusAborted);
    throw RunError(message);
  }
  MakeSafe();
  journal_.Append(RunCompleted{clock_.NowS()});
  journal_.Sync();
  meta_.SetStatus(kStatusComplete);
}

void Executor::RunActions(size_t first_action) {
  for (size_t i = first_action; i < plan_.actions.size(); ++i) {
    const PlannedAction& a = plan_.actions[i];
    current_action_ = i;
    action_started_s_ = clock_.NowS();
    measured_remaining_s_.reset();
    annotations_.Update([&](RowAnnotations& r) { r.step = static_cast<int>(a.step); });
    journal_.Append(ActionStarted{action_started_s_, i, a.step, Describe(a.action)});
    Report(true);
    Execute(a);
    journal_.Append(ActionCompleted{clock_.NowS(), i, a.step});
    const bool step_ends = i + 1 == plan_.actions.size() || plan_.actions[i + 1].step != a.step;
    if (step_ends) {
      recording_.Flush(true);
      journal_.Append(StepCompleted{clock_.NowS(), a.step});
      journal_.Sync();
    }
  }
}

void Executor::Execute(const PlannedAction& a) {
  std::visit(Overloaded{
                 [&](const PromptOperator& x) { instruments_.op->Prompt(x.text); },
                 [&](const MountOrientation& x) { Mount(x.orientation); },
                 [&](const CheckGravity& x) { GravityInterlock(a, x.orientation); },
                 [&](const CheckGyroAxis& x) { GyroInterlock(a, x.orientation, x.jog_rate_dps); },
                 [&](const SetTableRate& x) { Table().CommandRate(x.rate_dps, x.accel_dps2); },
                 [&](const WaitTableAtRate& x) { WaitTableAt(x.rate_dps, a.estimate_s); },
                 [&](const StopTable& x) {
                   Table().Stop(x.accel_dps2);
                   WaitTableAt(0.0, a.estimate_s);
                 },
                 [&](const SetChamberSetPoint& x) { Chamber().SetSetPointC(x.temp_c); },
                 [&](const WaitChamberSoak& x) {
                   WaitChamberInBand(x.temp_c, x.band_c, x.soak_s, a.estimate_s);
                 },
                 [&](const DownloadProfile& x) {
                   Chamber().DownloadProfile(x.profile.profile_name, x.profile.steps);
                 },
                 [&](const RunProfileLogging& x) { RunProfile(a, x.profile_name); },
                 [&](const SetAltitude& x) { Adts().SetAltitude(x.alt_ft, x.rate_ft_per_min); },
                 [&](const SetAirspeed& x) { Adts().SetAirspeed(x.cas_kt, x.rate_kt_per_min); },
                 [&](const calib::WaitAdtsStable&) { WaitAdtsStable(a.estimate_s); },
                 [&](const AcquirePackets& x) { Acquire(a, x.packets); },
                 [&](const LogForDuration& x) { LogFor(a, x.duration_s); },
             },
             a.action);
}

// A resumed run starts at a step whose earlier steps set up the rig: re-establish what they left
// (the fixture orientation, the chamber set point and band, the ADTS aims) before going on.
void Executor::RestoreState(size_t first_action) {
  std::optional<int> orientation;
  std::optional<double> set_point_c, band_c;
  std::optional<SetAltitude> altitude;
  std::optional<SetAirspeed> airspeed;
  for (size_t i = 0; i < first_action; ++i) {
    const Action& action = plan_.actions[i].action;
    if (const auto* m = std::get_if<MountOrientation>(&action)) orientation = m->orientation;
    if (const auto* s = std::get_if<SetChamberSetPoint>(&action)) set_point_c = s->temp_c;
    if (const auto* w = std::get_if<WaitChamberSoak>(&action)) band_c = w->band_c;
    if (const auto* s = std::get_if<SetAltitude>(&action)) altitude = *s;
    if (const auto* s = std::get_if<SetAirspeed>(&action)) airspeed = *s;
  }
  const bool mounts_itself =
      std::holds_alternative<MountOrientation>(plan_.actions[first_action].action);
  if (orientation && !mounts_itself) Mount(*orientation);
  if (set_point_c) {
    Chamber().SetSetPointC(*set_point_c);
    if (band_c) WaitChamberInBand(*set_point_c, *band_c, 0.0, 0.0);
  }
  if (altitude) Adts().SetAltitude(altitude->alt_ft, altitude->rate_ft_per_min);
  if (airspeed) Adts().SetAirspeed(airspeed->cas_kt, airspeed->rate_kt_per_min);
  if (altitude || airspeed) WaitAdtsStable(0.0);
  journal_.Append(StateRestored{clock_.NowS()});
}

void Executor::StopTableAndWait() {
  hil::RateTable& table = *instruments_.rate_table;
  table.Stop(options_.safe_stop_accel_dps2);
  // Bounded wait for rest: the slowest stop is from the table's top rate.
  const double deadline_s = clock_.NowS() + 360.0 / options_.safe_stop_accel_dps2 + 10.0;
  double rate_dps = table.ReadRateDps();
  while (std::abs(rate_dps) > options_.table_rate_tolerance_dps) {
    if (clock_.NowS() >= deadline_s) {
      throw RunError(
          fmt::format("{}: the rate table did not come to rest: {:.3f} deg/s after "
                      "stopping at {:g} deg/s^2",
                      Where(),
                      rate_dps,
                      options_.safe_stop_accel_dps2));
    }
    clock_.SleepS(PollIntervalS());
    rate_dps = table.ReadRateDps();
  }
}

void Executor::SafeStart() {
  RigSafeAtStart event;
  if (instruments_.rate_table != nullptr) {
    const double found_dps = instruments_.rate_table->ReadRateDps();
    event.table_found_dps = found_dps;
    if (std::abs(found_dps) > options_.table_rate_tolerance_dps) {
      progress_.Note(
          fmt::format("rate table found turning at {:.2f} deg/s: stopping it first", found_dps));
    }
    StopTableAndWait();
  }
  if (instruments_.chamber != nullptr) instruments_.chamber->Hold();
  if (instruments_.adts != nullptr) instruments_.adts->GoToGround();
  event.t_s = clock_.NowS();
  journal_.Append(event);
  journal_.Sync();
}

void Executor::MakeSafe() {
  const auto attempt = [&](const char* what, auto&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      journal_.Append(SafeStopFailed{clock_.NowS(), what, e.what()});
      progress_.Note(fmt::format("safe stop: {} failed: {}", what, e.what()));
    }
  };
  if (instruments_.rate_table != nullptr) {
    attempt("table stop", [&] { StopTableAndWait(); });
  }
  if (instruments_.chamber != nullptr)
    attempt("chamber hold", [&] { instruments_.chamber->Hold(); });
  if (instruments_.adts != nullptr)
    attempt("ADTS to ground", [&] { instruments_.adts->GoToGround(); });
  for (UnitLogger* l : loggers_) {
    attempt(l->role().c_str(), [&] { l->EndAcquisition().get(); });
  }
  attempt("recording flush", [&] { recording_.Flush(true); });
  journal_.Append(RigSafe{clock_.NowS()});
  journal_.Sync();
}

void Executor::StartAcquisitions(uint8_t tag, int64_t quota) {
  std::vector<std::future<void>> requests;
  for (UnitLogger* l : loggers_) requests.push_back(l->StartAcquisition(tag, quota));
  WaitAll(std::move(requests), loggers_, Where());
}

void Executor::EndAcquisitions() {
  std::vector<std::future<void>> requests;
  for (UnitLogger* l : loggers_) requests.push_back(l->EndAcquisition());
  WaitAll(std::move(requests), loggers_, Where());
}

void Executor::Mount(int orientation) {
  instruments_.op->Mount(roles_, orientation);
  annotations_.Update([&](RowAnnotations& r) { r.orientation = orientation; });
}

void Executor::Acquire(const PlannedAction& a, int64_t packets) {
  StartAcquisitions(a.tag, packets);
  WaitFor(
      fmt::format("{} packets tagged {} from every unit", packets, a.tag),
      a.estimate_s,
      [&] {
        for (const UnitLogger* l : loggers_) {
          if (l->acquired() < packets) return false;
        }
        return true;
      },
      [&] {
        std::vector<std::string> short_units;
        for (const UnitLogger* l : loggers_) {
          if (l->acquired() >= packets) continue;
          short_units.push_back(fmt::format("{} ({}) has {} of {} (lost {})",
                                            l->role(),
                                            l->serial(),
                                            l->acquired(),
                                            packets,
                                            l->lost()));
        }
        return "unit " + JoinRoles(short_units);
      });
  EndAcquisitions();
}

void Executor::LogFor(const PlannedAction& a, double duration_s) {
  StartAcquisitions(a.tag, -1);
  const double end_s = clock_.NowS() + duration_s;
  WaitFor(
      fmt::format("logging for {:.1f} s", duration_s),
      a.estimate_s,
      [&] { return clock_.NowS() >= end_s; },
      [] { return std::string("clock"); });
  EndAcquisitions();
}

void Executor::RunProfile(const PlannedAction& a, const std::string& name) {
  StartAcquisitions(a.tag, -1);
  Chamber().StartProfile(name);
  double pv_c = 0.0;
  WaitFor(
      fmt::format("{} profile '{}' to end", ChamberRole(), name),
      a.estimate_s,
      [&] {
        pv_c = annotations_.Get().chamber_c;
        return !Chamber().ProfileRunning();
      },
      [&] {
        return fmt::format(
            "{} still running the profile, process value {:.2f} degC", ChamberRole(), pv_c);
      });
  EndAcquisitions();
}

std::vector<RawAverage> Executor::AverageAll(const PlannedAction& a) {
  const auto count =
      static_cast<int64_t>(std::lround(options_.interlock_sample_s * options_.packet_rate_hz));
  std::vector<std::future<void>> requests;
  for (UnitLogger* l : loggers_) requests.push_back(l->BeginAverage(count));
  WaitAll(std::move(requests), loggers_, Where());
  std::vector<std::optional<RawAverage>> averages(loggers_.size());
  WaitFor(
      fmt::format("{} packets from every unit for the interlock", count),
      a.estimate_s,
      [&] {
        bool all = true;
        for (size_t u = 0; u < loggers_.size(); ++u) {
          if (!averages[u]) averages[u] = loggers_[u]->TakeAverage();
          all = all && averages[u].has_value();
        }
        return all;
      },
      [&] {
        std::vector<std::string> missing;
        for (size_t u = 0; u < loggers_.size(); ++u) {
          if (!averages[u])
            missing.push_back(fmt::format("{} ({})", loggers_[u]->role(), loggers_[u]->serial()));
        }
        return "no packets from unit " + JoinRoles(missing);
      });
  std::vector<RawAverage> out;
  for (auto& avg : averages) out.push_back(*avg);
  return out;
}

void Executor::GravityInterlock(const PlannedAction& a, int orientation) {
  for (int attempt = 1;; ++attempt) {
    const double t_start_s = clock_.NowS();
    const std::vector<RawAverage> averages = AverageAll(a);
    std::vector<std::string> failures;
    for (size_t u = 0; u < loggers_.size(); ++u) {
      const auto& reference = gravity_references_[u];
      const InterlockVerdict v = GravityVerdict(averages[u],
                                                orientation,
                                                reference ? &*reference : nullptr,
                                                options_.interlock_thresholds);
      if (!v.ok)
        failures.push_back(
            fmt::format("{} ({}): {}", loggers_[u]->role(), loggers_[u]->serial(), v.detail));
    }
    if (failures.empty()) {
      for (size_t u = 0; u < loggers_.size(); ++u) {
        gravity_references_[u] = GravityReference{averages[u], orientation};
      }
      return;
    }
    InterlockFailed(a, "gravity", t_start_s, failures, attempt, orientation);
  }
}

void Executor::GyroInterlock(const PlannedAction& a, int orientation, double jog_rate_dps) {
  for (int attempt = 1;; ++attempt) {
    const double t_start_s = clock_.NowS();
    const std::vector<RawAverage> rest = AverageAll(a);
    Table().CommandRate(jog_rate_dps, options_.jog_accel_dps2);
    WaitTableAt(jog_rate_dps, jog_rate_dps / options_.jog_accel_dps2);
    const std::vector<RawAverage> jog = AverageAll(a);
    Table().Stop(options_.jog_accel_dps2);
    WaitTableAt(0.0, jog_rate_dps / options_.jog_accel_dps2);
    std::vector<std::string> failures;
    for (size_t u = 0; u < loggers_.size(); ++u) {
      const InterlockVerdict v = GyroAxisVerdict(
          rest[u], jog[u], orientation, jog_rate_dps, options_.interlock_thresholds);
      if (!v.ok)
        failures.push_back(
            fmt::format("{} ({}): {}", loggers_[u]->role(), loggers_[u]->serial(), v.detail));
    }
    if (failures.empty()) return;
    InterlockFailed(a, "gyro axis", t_start_s, failures, attempt, orientation);
  }
}

void Executor::InterlockFailed(const PlannedAction& a,
                               const std::string& kind,
                               double t_start_s,
                               const std::vector<std::string>& failures,
                               int attempt,
                               int orientation) {
  if (instruments_.rate_table != nullptr)
    instruments_.rate_table->Stop(options_.safe_stop_accel_dps2);
  const double t_end_s = clock_.NowS();
  meta_.AddRejectedInterval(a.step, t_start_s, t_end_s, kind + " interlock failed");
  journal_.Append(calib::InterlockFailed{t_end_s, a.step, kind, attempt, failures});
  journal_.Sync();
  const std::string text = fmt::format("{}: {} interlock failed (attempt {} of {}): {}",
                                       Where(),
                                       kind,
                                       attempt,
                                       options_.interlock_attempts,
                                       JoinRoles(failures));
  progress_.Note(text);
  if (attempt >= options_.interlock_attempts) throw RunError(text);
  instruments_.op->Prompt(text + ". Check the mounting in orientation " +
                          std::to_string(orientation) + " and confirm.");
  Mount(orientation);
}

void Executor::WaitTableAt(double rate_dps, double estimate_s) {
  double last_dps = 0.0;
  WaitFor(
      fmt::format("rate_table at {:.2f} deg/s", rate_dps),
      estimate_s,
      [&] {
        last_dps = Table().ReadRateDps();
        annotations_.Update([&](RowAnnotations& r) { r.table_rate_dps = last_dps; });
        return std::abs(last_dps - rate_dps) <= options_.table_rate_tolerance_dps &&
               (rate_dps == 0.0 || Table().AtRate());
      },
      [&] { return fmt::format("rate_table reports {:.3f} deg/s", last_dps); });
}

void Executor::WaitChamberInBand(double target_c, double band_c, double soak_s, double estimate_s) {
  // The plan estimated from where the sequence left the chamber; it may start elsewhere (a first
  // step 10 degC away, a resume after a crash mid-ramp), so the budget also counts from its PV.
  const double start_c = Chamber().ReadProcessC();
  estimate_s = std::max(
      estimate_s, std::abs(target_c - start_c) / options_.chamber_ramp_c_per_min * 60.0 + soak_s);
  double pv_c = start_c;
  double inside_since_s = -1.0;  // clock time the value entered the band, < 0 when outside
  ChamberEta eta(target_c, band_c, soak_s);
  WaitFor(
      fmt::format(
          "{} inside {:.2f} +- {:.2f} degC for {:.0f} s", ChamberRole(), target_c, band_c, soak_s),
      estimate_s,
      [&] {
        pv_c = Chamber().ReadProcessC();
        annotations_.Update([&](RowAnnotations& r) { r.chamber_c = pv_c; });
        const double now_s = clock_.NowS();
        if (std::abs(pv_c - target_c) > band_c) {
          inside_since_s = -1.0;
        } else if (inside_since_s < 0.0) {
          inside_since_s = now_s;
        }
        eta.Observe(now_s, pv_c, inside_since_s);
        measured_remaining_s_ = eta.RemainingS();
        return inside_since_s >= 0.0 && now_s - inside_since_s >= soak_s;
      },
      [&] { return fmt::format("{} process value {:.2f} degC", ChamberRole(), pv_c); });
}

void Executor::WaitAdtsStable(double estimate_s) {
  hil::AirDataReading last;
  WaitFor(
      "adts (air data test set) stable",
      estimate_s,
      [&] {
        // Status first, then the reading: the reading the rows carry once the wait ends is then
        // taken after the test set said stable. Read first, it could predate the settling: in a
        // demo run the first 38 rows of a 50,000 ft point carried the reading of 46,000 ft.
        const bool stable = Adts().Stable();
        last = Adts().Read();
        annotations_.Update([&](RowAnnotations& r) {
          r.ps_ref_pa = last.ps_pa;
          r.qc_ref_pa = last.qc_pa;
        });
        return stable;
      },
      [&] {
        return fmt::format(
            "adts reads ps {:.1f} Pa, qc {:.1f} Pa, not stable", last.ps_pa, last.qc_pa);
      });
}

template <typename Done, typename State>
void Executor::WaitFor(const std::string& what, double estimate_s, Done done, State state) {
  const double margin_s = TimeoutMarginS();
  const double timeout_s = options_.timeout_factor * estimate_s + margin_s;
  const double start_s = clock_.NowS();
  for (;;) {
    Tick();
    if (done()) return;
    if (clock_.NowS() - start_s > timeout_s) {
      throw RunError(fmt::format(
          "{}: {} not reached within {:.0f} s ({:.0f} x estimate {:.1f} s + {:.0f} s): {}",
          Where(),
          what,
          timeout_s,
          options_.timeout_factor,
          estimate_s,
          margin_s,
          state()));
    }
    clock_.SleepS(PollIntervalS());
  }
}

double Executor::PollIntervalS() const {
  return std::max(options_.poll_interval_s, options_.min_poll_wall_s * clock_.time_scale());
}

double Executor::TimeoutMarginS() const {
  return std::max(options_.timeout_margin_s, options_.min_margin_wall_s * clock_.time_scale());
}

void Executor::Tick() {
  if (stop_.load()) throw RunInterrupted(Where() + ": stop requested");
  for (const UnitLogger* l : loggers_) {
    try {
      l->CheckHealthy();
    } catch (const std::exception& e) {
      throw RunError(
          fmt::format("{}: unit {} ({}): {}", Where(), l->role(), l->serial(), e.what()));
    }
  }
  RefreshReadings();
  Report(false);
}

void Executor::RefreshReadings() {
  const double now_s = clock_.NowS();
  if (now_s - last_refresh_s_ < options_.refresh_interval_s) return;
  last_refresh_s_ = now_s;
  RowAnnotations fresh = annotations_.Get();
  if (instruments_.chamber != nullptr) fresh.chamber_c = instruments_.chamber->ReadProcessC();
  if (instruments_.rate_table != nullptr)
    fresh.table_rate_dps = instruments_.rate_table->ReadRateDps();
  if (instruments_.adts != nullptr) {
    const hil::AirDataReading r = instruments_.adts->Read();
    fresh.ps_ref_pa = r.ps_pa;
    fresh.qc_ref_pa = r.qc_pa;
  }
  annotations_.Update([&](RowAnnotations& r) {
    r.chamber_c = fresh.chamber_c;
    r.table_rate_dps = fresh.table_rate_dps;
    r.ps_ref_pa = fresh.ps_ref_pa;
    r.qc_ref_pa = fresh.qc_ref_pa;
  });
}

void Executor::Report(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_report_ < std::chrono::duration<double>(options_.progress_interval_s))
    return;
  last_report_ = now;
  const PlannedAction& a = plan_.actions[current_action_];
  ProgressReport r;
  r.step = a.step;
  r.step_count = sequence_.steps.size();
  r.step_kind = StepKindName(sequence_.steps[a.step].body);
  r.action = current_action_;
  r.action_count = plan_.actions.size();
  r.action_text = Describe(a.action);
  r.t_s = clock_.NowS();
  // The running action by what it measures, if it can (a chamber wait: chamber_eta.h), else by
  // the plan; the actions after it by the plan.
  double remaining_s =
      measured_remaining_s_.value_or(std::max(0.0, a.estimate_s - (r.t_s - action_started_s_)));
  for (size_t i = current_action_ + 1; i < plan_.actions.size(); ++i)
    remaining_s += plan_.actions[i].estimate_s;
  r.eta_s = remaining_s;
  for (const UnitLogger* l : loggers_) {
    r.units.push_back({l->role(), l->serial(), l->rows(), l->acquired(), l->lost()});
  }
  progress_.Report(r);
}

std::string Executor::ChamberRole() const {
  return sequence_.unit_kind == UnitKind::kImu ? "imu_chamber" : "ads_chamber";
}

std::string Executor::Where() const {
  if (current_action_ >= plan_.actions.size()) return "after the last step";
  const PlannedAction& a = plan_.actions[current_action_];
  return fmt::format("step {} ({}, tag {}), action {} '{}'",
                     a.step,
                     StepKindName(sequence_.steps[a.step].body),
                     a.tag,
                     current_action_,
                     Describe(a.action));
}

hil::RateTable& Executor::Table() {
  if (instruments_.rate_table == nullptr)
    throw RunError(Where() + ": the station has no rate_table");
  return *instruments_.rate_table;
}

hil::Chamber& Executor::Chamber() {
  if (instruments_.chamber == nullptr)
    throw RunError(Where() + ": the station has no " + ChamberRole());
  return *instruments_.chamber;
}

hil::AirDataTestSet& Executor::Adts() {
  if (instruments_.adts == nullptr) throw RunError(Where() + ": the station has no adts");
  return *instruments_.adts;
}

}  // namespace adahrs::calib
