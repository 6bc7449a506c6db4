#include "calib/sequence/validation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/sequence/sequence_json.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "common/overloaded.h"

namespace adahrs::calib {

using common::Overloaded;

namespace {

// More rates than this in one gyro step is a typo, not a calibration: every rate is an
// acquisition of its own in the plan.
constexpr int kMaxGyroRatesPerStep = 1000;

std::string JoinProblems(const std::string& source, const std::vector<SequenceProblem>& problems) {
  std::string text = fmt::format("{}: sequence refused, {} problem{}:",
                                 source,
                                 problems.size(),
                                 problems.size() == 1 ? "" : "s");
  for (const SequenceProblem& p : problems) text += "\n  " + p.Format(source);
  return text;
}

// Collects the problems of one sequence; `Step(i)` gives the JSON path of step i.
class Checker {
 public:
  Checker(const SequenceLimits& limits, std::vector<SequenceProblem>& problems)
      : limits_(limits), problems_(problems) {}

  void Add(std::string path, std::string rule, std::string limit = "") {
    problems_.push_back({std::move(path), std::move(rule), std::move(limit)});
  }

  void Packets(const std::string& path, int64_t packets) {
    if (packets < 1 || packets > limits_.max_packets) {
      Add(path,
          fmt::format("packets must be 1…{}, got {}", limits_.max_packets, packets),
          fmt::format("acquisition limit {} packets", limits_.max_packets));
    }
  }

  void Orientation(const std::string& path, int code) {
    if (!IsOrientationCode(code)) {
      Add(path,
          fmt::format("orientation {} is not a fixture orientation code (11, 12, 21, 22, "
                      "31, 32)",
                      code));
    }
  }

  // A table rate, against the unit's gyro range and the table's rate limit.
  void TableRate(const std::string& path, double rate_dps) {
    if (std::abs(rate_dps) > limits_.unit_gyro_range_dps) {
      Add(path,
          fmt::format("rate {:g} deg/s beyond the unit's gyro range", rate_dps),
          fmt::format("unit gyro range ±{:g} deg/s", limits_.unit_gyro_range_dps));
    }
    if (std::abs(rate_dps) > limits_.table_max_rate_dps) {
      Add(path,
          fmt::format("rate {:g} deg/s beyond the {}'s rate limit", rate_dps, limits_.table_name),
          fmt::format("{} ±{:g} deg/s", limits_.table_name, limits_.table_max_rate_dps));
    }
    TableResolution(path, rate_dps);
  }

  // A rate or rate increment the table can be commanded in: a whole number of its resolution.
  void TableResolution(const std::string& path, double rate_dps) {
    const double steps = rate_dps / limits_.table_rate_resolution_dps;
    if (std::abs(steps - std::round(steps)) > 1e-9 * std::max(1.0, std::abs(steps))) {
      Add(path,
          fmt::format("{:g} deg/s is not a multiple of the {}'s rate resolution",
                      rate_dps,
                      limits_.table_name),
          fmt::format("{} commands rates in steps of {:g} deg/s",
                      limits_.table_name,
                      limits_.table_rate_resolution_dps));
    }
  }

  void TableAccel(const std::string& path, double accel_dps2) {
    if (!(accel_dps2 > 0.0) || accel_dps2 > limits_.table_max_accel_dps2) {
      Add(path,
          fmt::format("table acceleration must be in (0, {:g}] deg/s^2, got {:g}",
                      limits_.table_max_accel_dps2,
                      accel_dps2),
          fmt::format(
              "{} acceleration {:g} deg/s^2", limits_.table_name, limits_.table_max_accel_dps2));
    }
  }

  // A chamber set point, against the unit's rating and the chamber's range.
  void Temperature(const std::string& path, double temp_c) {
    if (temp_c < limits_.unit_temp_min_c || temp_c > limits_.unit_temp_max_c) {
      Add(path,
          fmt::format("temperature {:g} degC beyond the unit's rating", temp_c),
          fmt::format(
              "unit rating {:g}…{:g} degC", limits_.unit_temp_min_c, limits_.unit_temp_max_c));
    }
    if (temp_c < limits_.chamber_min_c || temp_c > limits_.chamber_max_c) {
      Add(path,
          fmt::format("temperature {:g} degC beyond the {}'s range", temp_c, limits_.chamber_name),
          fmt::format("{} {:g}…{:g} degC",
                      limits_.chamber_name,
                      limits_.chamber_min_c,
                      limits_.chamber_max_c));
    }
  }

  void RampRate(const std::string& path, double rate_c_per_min) {
    if (!(rate_c_per_min > 0.0) || rate_c_per_min > limits_.chamber_max_ramp_c_per_min) {
      Add(path,
          fmt::format("ramp rate must be in (0, {:g}] degC/min, got {:g}",
                      limits_.chamber_max_ramp_c_per_min,
                      rate_c_per_min),
          fmt::format("{} ramp rate {:g} degC/min",
                      limits_.chamber_name,
                      limits_.chamber_max_ramp_c_per_min));
    }
  }

  void StepDuration(const std::string& path, double duration_s) {
    if (!(duration_s > 0.0) || duration_s > limits_.chamber_max_step_duration_s) {
      Add(path,
          fmt::format("duration must be in (0, {:g}] s, got {:g}",
                      limits_.chamber_max_step_duration_s,
                      duration_s),
          fmt::format("{} step time 99:59:59", limits_.chamber_name));
    }
  }

  void Profile(const std::string& path,
               const ThermalProfileStep& profile,
               std::optional<double>& set_point_c) {
    const std::string& name = profile.profile_name;
    const bool name_ok =
        !name.empty() && name.size() <= 10 && std::all_of(name.begin(), name.end(), [](char c) {
          return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == ' ';
        });
    if (!name_ok) {
      Add(path + ".profile_name",
          fmt::format("profile name \"{}\" must be 1…10 of A–Z, 0–9 or space", name),
          fmt::format("{} profile name registers", limits_.chamber_name));
    }
    const auto& steps = profile.steps;
    const std::string steps_path = path + ".profile_steps";
    if (steps.empty() || steps.size() > static_cast<size_t>(limits_.chamber_max_profile_steps)) {
      Add(steps_path,
          fmt::format("a profile holds 1…{} steps, got {}",
                      limits_.chamber_max_profile_steps,
                      steps.size()),
          fmt::format(
              "{} {} profile steps", limits_.chamber_name, limits_.chamber_max_profile_steps));
    }
    if (!steps.empty() && !std::holds_alternative<F4End>(steps.back())) {
      Add(fmt::format("{}[{}]", steps_path, steps.size() - 1),
          "the last profile step must be an end step");
    }
    for (size_t i = 0; i < steps.size(); ++i) {
      const std::string p = fmt::format("{}[{}]", steps_path, i);
      const int step_number = static_cast<int>(i) + 1;  // F4 steps are numbered from 1
      std::visit(
          Overloaded{
              [&](const F4RampTime& s) {
                Temperature(p + ".target_c", s.target_c);
                StepDuration(p + ".duration_s", s.duration_s);
                if (set_point_c && s.duration_s > 0.0) {
                  const double rate_c_per_min =
                      std::abs(s.target_c - *set_point_c) / (s.duration_s / 60.0);
                  if (rate_c_per_min > limits_.chamber_max_ramp_c_per_min) {
                    Add(p + ".duration_s",
                        fmt::format("ramp from {:g} to {:g} degC in {:g} s is {:.3g} degC/min, "
                                    "faster than the chamber ramps",
                                    *set_point_c,
                                    s.target_c,
                                    s.duration_s,
                                    rate_c_per_min),
                        fmt::format("{} ramp rate {:g} degC/min",
                                    limits_.chamber_name,
                                    limits_.chamber_max_ramp_c_per_min));
                  }
                }
                set_point_c = s.target_c;
              },
              [&](const F4RampRate& s) {
                Temperature(p + ".target_c", s.target_c);
                RampRate(p + ".rate_c_per_min", s.rate_c_per_min);
                set_point_c = s.target_c;
              },
              [&](const F4Soak& s) { StepDuration(p + ".duration_s", s.duration_s); },
              [&](const F4Jump& s) {
                if (s.to_step < 1 || s.to_step >= step_number) {
                  Add(p + ".to_step",
                      fmt::format("jump from step {} to step {}: a jump goes back to an earlier "
                                  "step (1…{})",
                                  step_number,
                                  s.to_step,
                                  step_number - 1));
                } else if (!std::holds_alternative<F4RampTime>(steps[s.to_step - 1]) &&
                           !std::holds_alternative<F4RampRate>(steps[s.to_step - 1]) &&
                           !std::holds_alternative<F4Soak>(steps[s.to_step - 1])) {
                  Add(p + ".to_step",
                      fmt::format("jump to step {}, a {} step: a jump lands on a ramp or soak",
                                  s.to_step,
                                  F4StepTypeName(steps[s.to_step - 1])));
                }
                if (s.count < 1 || s.count > limits_.chamber_max_jump_count) {
                  Add(p + ".count",
                      fmt::format(
                          "jump count {} outside 1…{}", s.count, limits_.chamber_max_jump_count),
                      fmt::format("{} jump count {}",
                                  limits_.chamber_name,
                                  limits_.chamber_max_jump_count));
                }
              },
              [&](const F4End& s) {
                if (i + 1 != steps.size()) {
                  Add(p + ".type", "an end step must be the last profile step");
                }
                if (s.action == F4EndAction::kIdle) {
                  Temperature(p + ".idle_c", s.idle_c);
                  set_point_c = s.idle_c;
                } else if (s.action != F4EndAction::kHold) {
                  set_point_c.reset();
                }
              },
          },
          steps[i]);
    }
  }

  void Altitude(const std::string& path, const AltitudeStep& s) {
    const std::string alt_path = path + ".alt_ft";
    if (s.alt_ft < limits_.unit_alt_min_ft || s.alt_ft > limits_.unit_alt_max_ft) {
      Add(alt_path,
          fmt::format("altitude {:g} ft outside the unit's range", s.alt_ft),
          fmt::format(
              "unit altitude {:g}…{:g} ft", limits_.unit_alt_min_ft, limits_.unit_alt_max_ft));
    }
    if (s.alt_ft < limits_.adts_alt_min_ft || s.alt_ft > limits_.adts_alt_max_ft) {
      Add(alt_path,
          fmt::format("altitude {:g} ft outside the {}'s range", s.alt_ft, limits_.adts_name),
          fmt::format("{} {:g}…{:g} ft",
                      limits_.adts_name,
                      limits_.adts_alt_min_ft,
                      limits_.adts_alt_max_ft));
    }
    // The ISA model covers −16,400…65,600 ft; beyond it the range checks above already refuse.
    constexpr double kIsaMin_ft = -16000.0;
    constexpr double kIsaMax_ft = 65000.0;
    if (s.alt_ft >= kIsaMin_ft && s.alt_ft <= kIsaMax_ft) {
      const double ps_pa = common::IsaStaticPressurePaFromFt(s.alt_ft);
      if (ps_pa > limits_.ads_static_max_pa) {
        Add(alt_path,
            fmt::format("altitude {:g} ft is a static pressure of {:.0f} Pa ({:.3f} psi), above "
                        "the ADS static sensor's limit",
                        s.alt_ft,
                        ps_pa,
                        common::PaToPsi(ps_pa)),
            fmt::format("ADS static pressure {:.0f} Pa ({:.3f} psi)",
                        limits_.ads_static_max_pa,
                        common::PaToPsi(limits_.ads_static_max_pa)));
      }
    }
    const double max_rate =
        std::min(limits_.ads_max_alt_rate_ft_per_min, limits_.adts_max_alt_rate_ft_per_min);
    if (!(s.rate_ft_per_min > 0.0) || s.rate_ft_per_min > max_rate) {
      Add(path + ".rate_ft_per_min",
          fmt::format(
              "altitude rate must be in (0, {:g}] ft/min, got {:g}", max_rate, s.rate_ft_per_min),
          fmt::format("ADS safe slew {:g} ft/min, {} {:g} ft/min",
                      limits_.ads_max_alt_rate_ft_per_min,
                      limits_.adts_name,
                      limits_.adts_max_alt_rate_ft_per_min));
    }
  }

  void Airspeed(const std::string& path, const AirspeedStep& s) {
    const std::string cas_path = path + ".cas_kt";
    if (s.cas_kt < 0.0 || s.cas_kt > limits_.unit_cas_max_kt) {
      Add(cas_path,
          fmt::format("airspeed {:g} kt outside the unit's range", s.cas_kt),
          fmt::format("unit airspeed 0…{:g} kt", limits_.unit_cas_max_kt));
    }
    if (s.cas_kt < 0.0 || s.cas_kt > limits_.adts_cas_max_kt) {
      Add(cas_path,
          fmt::format("airspeed {:g} kt outside the {}'s range", s.cas_kt, limits_.adts_name),
          fmt::format("{} 0…{:g} kt", limits_.adts_name, limits_.adts_cas_max_kt));
    }
    // The subsonic relation holds to a0 = 661.5 kt; beyond it the unit check has refused.
    const double a0_kt = common::MpsToKt(common::SeaLevelSpeedOfSoundMps());
    if (s.cas_kt >= 0.0 && s.cas_kt <= a0_kt) {
      const double qc_pa = common::ImpactPressurePaFromKt(s.cas_kt);
      if (qc_pa > limits_.ads_pitot_max_pa) {
        Add(cas_path,
            fmt::format("airspeed {:g} kt is an impact pressure of {:.0f} Pa, above the ADS "
                        "pitot sensor's limit",
                        s.cas_kt,
                        qc_pa),
            fmt::format("ADS pitot pressure {:.0f} Pa", limits_.ads_pitot_max_pa));
      }
    }
    const double max_rate =
        std::min(limits_.ads_max_cas_rate_kt_per_min, limits_.adts_max_cas_rate_kt_per_min);
    if (!(s.rate_kt_per_min > 0.0) || s.rate_kt_per_min > max_rate) {
      Add(path + ".rate_kt_per_min",
          fmt::format(
              "airspeed rate must be in (0, {:g}] kt/min, got {:g}", max_rate, s.rate_kt_per_min),
          fmt::format("ADS safe slew {:g} kt/min, {} {:g} kt/min",
                      limits_.ads_max_cas_rate_kt_per_min,
                      limits_.adts_name,
                      limits_.adts_max_cas_rate_kt_per_min));
    }
  }

  void Gyro(const std::string& path, const GyroStep& s) {
    Orientation(path + ".orientation", s.orientation);
    Packets(path + ".packets", s.packets);
    TableAccel(path + ".table_accel_dps2", s.table_accel_dps2);
    if (!(s.rate_increment_dps > 0.0)) {
      Add(path + ".rate_increment_dps",
          fmt::format("rate increment must be positive, got {:g}", s.rate_increment_dps));
      return;
    }
    if (s.rate_min_dps > s.rate_max_dps) {
      Add(path + ".rate_min_dps",
          fmt::format(
              "rate_min {:g} deg/s above rate_max {:g} deg/s", s.rate_min_dps, s.rate_max_dps));
      return;
    }
    // At least one step of the table: a smaller increment would command the same rate over and
    // over (1e-9 deg/s once expanded 3e11 rates and ran out of memory).
    if (s.rate_increment_dps < limits_.table_rate_resolution_dps * (1.0 - 1e-9)) {
      Add(path + ".rate_increment_dps",
          fmt::format("rate increment {:g} deg/s is below the {}'s rate resolution",
                      s.rate_increment_dps,
                      limits_.table_name),
          fmt::format("{} commands rates in steps of {:g} deg/s",
                      limits_.table_name,
                      limits_.table_rate_resolution_dps));
      return;
    }
    // Whole number of increments, to a part in 10⁹ of the span (decimal fractions like 0.1 are
    // not exact in binary).
    const double intervals = (s.rate_max_dps - s.rate_min_dps) / s.rate_increment_dps;
    if (intervals + 1.0 > kMaxGyroRatesPerStep) {
      Add(path + ".rate_increment_dps",
          fmt::format("{:g}…{:g} deg/s by {:g} deg/s is {:.0f} rates",
                      s.rate_min_dps,
                      s.rate_max_dps,
                      s.rate_increment_dps,
                      std::floor(intervals) + 1.0),
          fmt::format("at most {} rates in one gyro step", kMaxGyroRatesPerStep));
      return;
    }
    if (std::abs(intervals - std::round(intervals)) > 1e-9 * std::max(1.0, intervals)) {
      Add(path + ".rate_increment_dps",
          fmt::format("{:g}…{:g} deg/s is not a whole number of {:g} deg/s increments",
                      s.rate_min_dps,
                      s.rate_max_dps,
                      s.rate_increment_dps));
    }
    TableRate(path + ".rate_min_dps", s.rate_min_dps);
    TableRate(path + ".rate_max_dps", s.rate_max_dps);
    TableResolution(path + ".rate_increment_dps", s.rate_increment_dps);
  }

  void KindAllowed(const std::string& path, const StepBody& body, UnitKind kind) {
    const bool imu_only = std::holds_alternative<AccelStep>(body) ||
                          std::holds_alternative<GyroStep>(body) ||
                          std::holds_alternative<CrossAxisStep>(body);
    const bool ads_only = std::holds_alternative<AltitudeStep>(body) ||
                          std::holds_alternative<AirspeedStep>(body) ||
                          std::holds_alternative<LogStep>(body);
    if ((imu_only && kind != UnitKind::kImu) || (ads_only && kind != UnitKind::kAds)) {
      Add(path + ".kind",
          fmt::format(
              "a {} step has no place in an {} sequence", StepKindName(body), UnitKindName(kind)));
    }
  }

  void Tags(const Sequence& sequence, const std::vector<std::string>& step_paths) {
    const size_t problems_before = problems_.size();
    std::vector<int> first_user(256, -1);
    for (size_t i = 0; i < sequence.steps.size(); ++i) {
      const std::optional<int>& tag = sequence.steps[i].tag;
      if (!tag) continue;
      if (*tag < 1 || *tag > 255) {
        Add(step_paths[i] + ".tag", fmt::format("TAG {} outside 1…255 (one byte, 0 unused)", *tag));
        continue;
      }
      if (first_user[static_cast<size_t>(*tag)] >= 0) {
        Add(step_paths[i] + ".tag",
            fmt::format("TAG {} already used by {}",
                        *tag,
                        step_paths[static_cast<size_t>(first_user[static_cast<size_t>(*tag)])]));
      } else {
        first_user[static_cast<size_t>(*tag)] = static_cast<int>(i);
      }
    }
    if (problems_.size() == problems_before) {  // stated TAGs valid: assign the others
      try {
        EffectiveTags(sequence);
      } catch (const std::invalid_argument& e) {
        Add("$.steps", e.what(), "one-byte TAG 1…255, consecutive steps distinct");
      }
    }
  }

 private:
  const SequenceLimits& limits_;
  std::vector<SequenceProblem>& problems_;
};

// The limits a sequence of `kind` is checked against: an ADS batch's chamber is the ADS bench's.
SequenceLimits BatchLimits(const SequenceLimits& limits, UnitKind kind) {
  SequenceLimits batch = limits;
  if (kind == UnitKind::kAds) {
    batch.chamber_name = limits.ads_chamber_name;
    batch.chamber_min_c = limits.ads_chamber_min_c;
    batch.chamber_max_c = limits.ads_chamber_max_c;
    batch.chamber_max_ramp_c_per_min = limits.ads_chamber_max_ramp_c_per_min;
  }
  return batch;
}

std::vector<SequenceProblem> Validate(const Sequence& sequence,
                                      const SequenceLimits& all_limits,
                                      const std::vector<std::string>& step_paths) {
  const SequenceLimits limits = BatchLimits(all_limits, sequence.unit_kind);
  std::vector<SequenceProblem> problems;
  Checker check(limits, problems);
  if (sequence.steps.empty()) check.Add("$.steps", "a sequence needs at least one step");
  check.Tags(sequence, step_paths);
  std::optional<double> set_point_c;  // the chamber's set point where the sequence knows it
  for (size_t i = 0; i < sequence.steps.size(); ++i) {
    const std::string& p = step_paths[i];
    const StepBody& body = sequence.steps[i].body;
    check.KindAllowed(p, body, sequence.unit_kind);
    std::visit(
        Overloaded{
            [&](const AccelStep& s) {
              check.Orientation(p + ".orientation", s.orientation);
              check.Packets(p + ".packets", s.packets);
            },
            [&](const GyroStep& s) { check.Gyro(p, s); },
            [&](const TargetTemperatureStep& s) {
              check.Temperature(p + ".target_c", s.target_c);
              if (!(s.band_c > 0.0)) {
                check.Add(p + ".band_c", fmt::format("band must be positive, got {:g}", s.band_c));
              }
              if (!(s.soak_s >= 0.0)) {
                check.Add(p + ".soak_s",
                          fmt::format("soak must not be negative, got {:g}", s.soak_s));
              }
              set_point_c = s.target_c;
            },
            [&](const CrossAxisStep& s) {
              check.Packets(p + ".packets", s.packets);
              check.TableRate(p + ".rate_dps", s.rate_dps);
              if (!(s.rate_dps != 0.0)) {
                check.Add(p + ".rate_dps", "the cross-axis rate must not be zero");
              }
              check.TableAccel(p + ".table_accel_dps2", s.table_accel_dps2);
            },
            [&](const ThermalProfileStep& s) {
              if (sequence.unit_kind == UnitKind::kAds && !limits.ads_chamber_runs_profiles) {
                check.Add(p + ".kind",
                          fmt::format("the ADS bench's {} runs set points only: its driver "
                                      "downloads no profile (use target_temperature and log "
                                      "steps)",
                                      limits.ads_chamber_name),
                          fmt::format("{} driver: set points only", limits.ads_chamber_name));
                return;
              }
              check.Profile(p, s, set_point_c);
            },
            [&](const AltitudeStep& s) { check.Altitude(p, s); },
            [&](const AirspeedStep& s) { check.Airspeed(p, s); },
            [&](const LogStep& s) {
              if (s.packets) check.Packets(p + ".packets", *s.packets);
              if (s.duration_s &&
                  (!(*s.duration_s > 0.0) || *s.duration_s > limits.max_log_duration_s)) {
                check.Add(p + ".duration_s",
                          fmt::format("log duration must be in (0, {:g}] s, got {:g}",
                                      limits.max_log_duration_s,
                                      *s.duration_s),
                          fmt::format("log duration {:g} s", limits.max_log_duration_s));
              }
            },
            [&](const PromptStep& s) {
              if (s.text.empty()) check.Add(p + ".text", "a prompt needs its text");
            },
        },
        body);
  }
  return problems;
}

std::vector<std::string> StepPaths(const std::vector<size_t>& file_index) {
  std::vector<std::string> paths;
  for (size_t i : file_index) paths.push_back(fmt::format("$.steps[{}]", i));
  return paths;
}

}  // namespace

std::string SequenceProblem::Format(const std::string& source) const {
  std::string text = source + ": " + path + ": " + rule;
  if (!limit.empty()) text += " (limit: " + limit + ")";
  return text;
}

SequenceError::SequenceError(std::string source, std::vector<SequenceProblem> problems)
    : std::runtime_error(JoinProblems(source, problems)),
      source_(std::move(source)),
      problems_(std::move(problems)) {}

std::vector<SequenceProblem> ValidateSequence(const Sequence& sequence,
                                              const SequenceLimits& limits) {
  std::vector<size_t> index(sequence.steps.size());
  for (size_t i = 0; i < index.size(); ++i) index[i] = i;
  return Validate(sequence, limits, StepPaths(index));
}

namespace {

// Structural problems of `parsed`, then the limit problems of the steps that could be read.
std::vector<SequenceProblem> CheckParsed(ParsedSequence& parsed, const SequenceLimits& limits) {
  std::vector<SequenceProblem> problems = parsed.problems;
  // The steps that could be read are checked too, under their paths in the file; an empty list
  // is only a problem of its own when the file really holds no step.
  const bool had_steps_error =
      std::any_of(problems.begin(), problems.end(), [](const SequenceProblem& p) {
        return p.path.starts_with("$.steps");
      });
  std::vector<SequenceProblem> limit_problems =
      Validate(parsed.sequence, limits, StepPaths(parsed.file_step_index));
  for (SequenceProblem& p : limit_problems) {
    if (had_steps_error && p.path == "$.steps" && parsed.sequence.steps.empty()) continue;
    problems.push_back(std::move(p));
  }
  return problems;
}

}  // namespace

std::vector<SequenceProblem> CheckSequenceFile(const std::string& file_path,
                                               const SequenceLimits& limits) {
  ParsedSequence parsed = ParseSequenceFile(file_path);
  return CheckParsed(parsed, limits);
}

Sequence LoadValidSequence(const std::string& file_path, const SequenceLimits& limits) {
  ParsedSequence parsed = ParseSequenceFile(file_path);
  std::vector<SequenceProblem> problems = CheckParsed(parsed, limits);
  if (!problems.empty()) throw SequenceError(file_path, std::move(problems));
  return std::move(parsed.sequence);
}

}  // namespace adahrs::calib
