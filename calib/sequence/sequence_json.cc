#include "calib/sequence/sequence_json.h"

#include <fstream>
#include <functional>
#include <string_view>

#include "common/overloaded.h"
#include "common/param_reader.h"
#include "common/unit_kind.h"

namespace adahrs::calib {

using common::Overloaded;

namespace {

using common::ParamError;
using common::ParamReader;

// The reader checks form; limits are validation's. Any finite value within this is well formed.
constexpr double kAnyFinite = 1e9;
constexpr int64_t kAnyInteger = 1000000000;

// ParamError::what() is "<source>: <path>: <message>"; split it back into a problem.
SequenceProblem ProblemFromParamError(const ParamError& error, const std::string& source) {
  std::string_view text = error.what();
  if (text.starts_with(source + ": ")) text.remove_prefix(source.size() + 2);
  const size_t colon = text.find(": ");
  if (colon == std::string_view::npos) return {"$", std::string(text), ""};
  return {std::string(text.substr(0, colon)), std::string(text.substr(colon + 2)), ""};
}

// Runs `read`, turning a ParamError into a problem; returns whether it succeeded.
bool Collect(const std::function<void()>& read,
             const std::string& source,
             std::vector<SequenceProblem>& problems) {
  try {
    read();
    return true;
  } catch (const ParamError& e) {
    problems.push_back(ProblemFromParamError(e, source));
    return false;
  }
}

double AnyNumber(const ParamReader& r, std::string_view key, std::string_view unit) {
  return r.Number(key, -kAnyFinite, kAnyFinite, unit);
}

int AnyInt(const ParamReader& r, std::string_view key) {
  return static_cast<int>(r.Integer(key, -kAnyInteger, kAnyInteger));
}

F4ProfileStep ReadF4Step(const ParamReader& r) {
  const std::string type = r.String("type");
  F4ProfileStep step;
  if (type == "ramp_time") {
    step = F4RampTime{AnyNumber(r, "target_c", "degC"), AnyNumber(r, "duration_s", "s")};
  } else if (type == "ramp_rate") {
    step = F4RampRate{AnyNumber(r, "target_c", "degC"), AnyNumber(r, "rate_c_per_min", "degC/min")};
  } else if (type == "soak") {
    step = F4Soak{AnyNumber(r, "duration_s", "s")};
  } else if (type == "jump") {
    step = F4Jump{AnyInt(r, "to_step"), AnyInt(r, "count")};
  } else if (type == "end") {
    const std::string action = r.String("action");
    F4End end;
    if (action == "hold") {
      end.action = F4EndAction::kHold;
    } else if (action == "control_off") {
      end.action = F4EndAction::kControlOff;
    } else if (action == "all_off") {
      end.action = F4EndAction::kAllOff;
    } else if (action == "idle") {
      end.action = F4EndAction::kIdle;
      end.idle_c = AnyNumber(r, "idle_c", "degC");
    } else {
      r.Fail(r.path() + ".action",
             "unknown end action \"" + action + "\"; one of hold, control_off, all_off, idle");
    }
    step = end;
  } else {
    r.Fail(
        r.path() + ".type",
        "unknown profile step type \"" + type + "\"; one of ramp_time, ramp_rate, soak, jump, end");
  }
  r.ExpectAllKeysUsed();
  return step;
}

// The number of elements of the array under `key`, or a ParamError naming it. ParamReader has
// no array-size accessor and records a key as used only when an accessor requires it; for an
// empty array there is no element to read, so the key is required through Child(), whose
// "expected a JSON object" complaint about the array is expected here and dropped.
size_t ArraySize(const nlohmann::json& object, const ParamReader& r, std::string_view key) {
  const auto it = object.find(std::string(key));
  if (it == object.end()) r.Fail(r.path() + "." + std::string(key), "missing key");
  if (!it->is_array()) r.Fail(r.path() + "." + std::string(key), "expected an array");
  if (it->empty()) {
    try {
      r.Child(key);
    } catch (const ParamError&) {
    }
  } else {
    r.Element(key, 0, it->size());
  }
  return it->size();
}

ThermalProfileStep ReadThermalProfile(const nlohmann::json& object,
                                      const ParamReader& r,
                                      const std::string& source,
                                      std::vector<SequenceProblem>& problems) {
  ThermalProfileStep profile;
  profile.profile_name = r.String("profile_name");
  const size_t count = ArraySize(object, r, "profile_steps");
  for (size_t i = 0; i < count; ++i) {
    Collect([&] { profile.steps.push_back(ReadF4Step(r.Element("profile_steps", i, count))); },
            source,
            problems);
  }
  return profile;
}

StepBody ReadBody(const std::string& kind,
                  const nlohmann::json& object,
                  const ParamReader& r,
                  const std::string& source,
                  std::vector<SequenceProblem>& problems) {
  if (kind == "accel") {
    return AccelStep{AnyInt(r, "orientation"), r.Integer("packets", -kAnyInteger, kAnyInteger)};
  }
  if (kind == "gyro") {
    GyroStep s;
    s.orientation = AnyInt(r, "orientation");
    s.packets = r.Integer("packets", -kAnyInteger, kAnyInteger);
    s.rate_min_dps = AnyNumber(r, "rate_min_dps", "deg/s");
    s.rate_max_dps = AnyNumber(r, "rate_max_dps", "deg/s");
    s.rate_increment_dps = AnyNumber(r, "rate_increment_dps", "deg/s");
    s.table_accel_dps2 = AnyNumber(r, "table_accel_dps2", "deg/s^2");
    return s;
  }
  if (kind == "target_temperature") {
    return TargetTemperatureStep{AnyNumber(r, "target_c", "degC"),
                                 AnyNumber(r, "band_c", "degC"),
                                 AnyNumber(r, "soak_s", "s")};
  }
  if (kind == "cross_axis") {
    return CrossAxisStep{r.Integer("packets", -kAnyInteger, kAnyInteger),
                         AnyNumber(r, "rate_dps", "deg/s"),
                         AnyNumber(r, "table_accel_dps2", "deg/s^2")};
  }
  if (kind == "thermal_profile") return ReadThermalProfile(object, r, source, problems);
  if (kind == "altitude") {
    return AltitudeStep{AnyNumber(r, "alt_ft", "ft"), AnyNumber(r, "rate_ft_per_min", "ft/min")};
  }
  if (kind == "airspeed") {
    return AirspeedStep{AnyNumber(r, "cas_kt", "kt"), AnyNumber(r, "rate_kt_per_min", "kt/min")};
  }
  if (kind == "log") {
    LogStep s;
    const bool by_packets = r.Has("packets");
    const bool by_duration = r.Has("duration_s");
    if (by_packets == by_duration) {
      r.Fail(r.path(), "a log step takes exactly one of packets and duration_s");
    }
    if (by_packets) s.packets = r.Integer("packets", -kAnyInteger, kAnyInteger);
    if (by_duration) s.duration_s = AnyNumber(r, "duration_s", "s");
    return s;
  }
  if (kind == "prompt") return PromptStep{r.String("text")};
  r.Fail(r.path() + ".kind",
         "unknown step kind \"" + kind +
             "\"; one of accel, gyro, target_temperature, cross_axis, thermal_profile, "
             "altitude, airspeed, log, prompt");
}

}  // namespace

ParsedSequence ParseSequence(const nlohmann::json& document, const std::string& source) {
  ParsedSequence parsed;
  std::vector<SequenceProblem>& problems = parsed.problems;
  Sequence& sequence = parsed.sequence;
  if (!document.is_object()) {
    problems.push_back({"$", "expected a JSON object", ""});
    return parsed;
  }
  const ParamReader r(document, source);
  Collect([&] { r.Integer("format_version", Sequence::kFormatVersion, Sequence::kFormatVersion); },
          source,
          problems);
  Collect([&] { sequence.name = r.String("name"); }, source, problems);
  Collect([&] { sequence.description = r.String("description"); }, source, problems);
  Collect(
      [&] {
        const std::string kind = r.String("unit_kind");
        const std::optional<UnitKind> parsed = common::ParseUnitKind(kind);
        if (!parsed) r.Fail("$.unit_kind", "unknown unit kind \"" + kind + "\"; one of imu, ads");
        sequence.unit_kind = *parsed;
      },
      source,
      problems);
  size_t count = 0;
  Collect([&] { count = ArraySize(document, r, "steps"); }, source, problems);
  for (size_t i = 0; i < count; ++i) {
    Collect(
        [&] {
          const ParamReader s = r.Element("steps", i, count);
          Step step;
          if (s.Has("tag")) step.tag = AnyInt(s, "tag");
          const size_t problems_before = problems.size();
          step.body = ReadBody(s.String("kind"), document["steps"][i], s, source, problems);
          s.ExpectAllKeysUsed();
          if (problems.size() == problems_before) {
            sequence.steps.push_back(std::move(step));
            parsed.file_step_index.push_back(i);
          }
        },
        source,
        problems);
  }
  Collect([&] { r.ExpectAllKeysUsed(); }, source, problems);
  return parsed;
}

ParsedSequence ParseSequenceFile(const std::string& file_path) {
  nlohmann::json document;
  try {
    document = ParamReader::LoadFile(file_path);
  } catch (const ParamError& e) {
    ParsedSequence parsed;
    std::string rule = e.what();
    if (rule.starts_with(file_path + ": ")) rule.erase(0, file_path.size() + 2);
    parsed.problems.push_back({"$", rule, ""});
    return parsed;
  }
  return ParseSequence(document, file_path);
}

Sequence SequenceFromJson(const nlohmann::json& document, const std::string& source) {
  ParsedSequence parsed = ParseSequence(document, source);
  if (!parsed.problems.empty()) throw SequenceError(source, std::move(parsed.problems));
  return std::move(parsed.sequence);
}

nlohmann::ordered_json SequenceToJson(const Sequence& sequence) {
  nlohmann::ordered_json out;
  out["format_version"] = Sequence::kFormatVersion;
  out["name"] = sequence.name;
  out["description"] = sequence.description;
  out["unit_kind"] = UnitKindName(sequence.unit_kind);
  out["steps"] = nlohmann::ordered_json::array();
  for (const Step& step : sequence.steps) {
    nlohmann::ordered_json s;
    s["kind"] = StepKindName(step.body);
    if (step.tag) s["tag"] = *step.tag;
    std::visit(Overloaded{
                   [&](const AccelStep& a) {
                     s["orientation"] = a.orientation;
                     s["packets"] = a.packets;
                   },
                   [&](const GyroStep& g) {
                     s["orientation"] = g.orientation;
                     s["packets"] = g.packets;
                     s["rate_min_dps"] = g.rate_min_dps;
                     s["rate_max_dps"] = g.rate_max_dps;
                     s["rate_increment_dps"] = g.rate_increment_dps;
                     s["table_accel_dps2"] = g.table_accel_dps2;
                   },
                   [&](const TargetTemperatureStep& t) {
                     s["target_c"] = t.target_c;
                     s["band_c"] = t.band_c;
                     s["soak_s"] = t.soak_s;
                   },
                   [&](const CrossAxisStep& c) {
                     s["packets"] = c.packets;
                     s["rate_dps"] = c.rate_dps;
                     s["table_accel_dps2"] = c.table_accel_dps2;
                   },
                   [&](const ThermalProfileStep& p) {
                     s["profile_name"] = p.profile_name;
                     s["profile_steps"] = nlohmann::ordered_json::array();
                     for (const F4ProfileStep& f4 : p.steps) {
                       nlohmann::ordered_json e;
                       e["type"] = F4StepTypeName(f4);
                       std::visit(Overloaded{
                                      [&](const F4RampTime& x) {
                                        e["target_c"] = x.target_c;
                                        e["duration_s"] = x.duration_s;
                                      },
                                      [&](const F4RampRate& x) {
                                        e["target_c"] = x.target_c;
                                        e["rate_c_per_min"] = x.rate_c_per_min;
                                      },
                                      [&](const F4Soak& x) { e["duration_s"] = x.duration_s; },
                                      [&](const F4Jump& x) {
                                        e["to_step"] = x.to_step;
                                        e["count"] = x.count;
                                      },
                                      [&](const F4End& x) {
                                        e["action"] = F4EndActionName(x.action);
                                        if (x.action == F4EndAction::kIdle) e["idle_c"] = x.idle_c;
                                      },
                                  },
                                  f4);
                       s["profile_steps"].push_back(std::move(e));
                     }
                   },
                   [&](const AltitudeStep& a) {
                     s["alt_ft"] = a.alt_ft;
                     s["rate_ft_per_min"] = a.rate_ft_per_min;
                   },
                   [&](const AirspeedStep& a) {
                     s["cas_kt"] = a.cas_kt;
                     s["rate_kt_per_min"] = a.rate_kt_per_min;
                   },
                   [&](const LogStep& l) {
                     if (l.packets) s["packets"] = *l.packets;
                     if (l.duration_s) s["duration_s"] = *l.duration_s;
                   },
                   [&](const PromptStep& p) { s["text"] = p.text; },
               },
               step.body);
    out["steps"].push_back(std::move(s));
  }
  return out;
}

void SaveSequence(const Sequence& sequence, const std::string& file_path) {
  std::ofstream out(file_path);
  if (!out) throw std::runtime_error(file_path + ": cannot open for writing");
  out << SequenceToJson(sequence).dump(2) << "\n";
  if (!out) throw std::runtime_error(file_path + ": write failed");
}

}  // namespace adahrs::calib
