#include "hil/recording/recording_meta.h"

#include <algorithm>
#include <cmath>

#include "common/param_reader.h"
#include "hil/recording/recording_error.h"

namespace adahrs::hil {
namespace {

using nlohmann::json;

using common::ParamReader;

// An optional key of meta.json: absent is nullopt; present, it must be of its type.
std::optional<std::string> OptionalString(const ParamReader& r, const char* key) {
  return r.Has(key) ? std::optional(r.String(key)) : std::nullopt;
}
std::optional<double> OptionalNumber(const ParamReader& r,
                                     const char* key,
                                     double max,
                                     const char* unit) {
  return r.Has(key) ? std::optional(r.Number(key, 0.0, max, unit)) : std::nullopt;
}
std::optional<int64_t> OptionalInteger(const ParamReader& r, const char* key, int64_t max) {
  return r.Has(key) ? std::optional(r.Integer(key, 0, max)) : std::nullopt;
}

RecordingUnit UnitFromJson(const ParamReader& r) {
  RecordingUnit u;
  u.role = OptionalString(r, "role").value_or("");
  if (const std::optional<std::string> kind = OptionalString(r, "kind")) {
    u.kind = common::ParseUnitKind(*kind);
    if (!u.kind) r.Fail(r.path() + ".kind", json(*kind).dump() + " is not \"imu\" or \"ads\"");
  }
  u.serial = OptionalString(r, "serial").value_or("");
  u.serial_number = OptionalInteger(r, "serial_number", INT64_MAX);
  u.firmware = OptionalString(r, "firmware");
  u.slot = OptionalInteger(r, "slot", INT64_MAX);
  u.constants_version = OptionalInteger(r, "constants_version", INT64_MAX);
  u.mode = OptionalInteger(r, "mode", INT64_MAX);
  u.line_buffering_s = OptionalNumber(r, "line_buffering_s", 1e6, "s");
  u.clock_drift_ppm = OptionalNumber(r, "clock_drift_ppm", 1e6, "ppm");
  return u;
}

json UnitToJson(const RecordingUnit& u) {
  json j = json::object();
  if (!u.role.empty()) j["role"] = u.role;
  if (u.kind) j["kind"] = common::UnitKindName(*u.kind);
  if (!u.serial.empty()) j["serial"] = u.serial;
  if (u.serial_number) j["serial_number"] = *u.serial_number;
  if (u.firmware) j["firmware"] = *u.firmware;
  if (u.slot) j["slot"] = *u.slot;
  if (u.constants_version) j["constants_version"] = *u.constants_version;
  if (u.mode) j["mode"] = *u.mode;
  if (u.line_buffering_s) j["line_buffering_s"] = *u.line_buffering_s;
  if (u.clock_drift_ppm) j["clock_drift_ppm"] = *u.clock_drift_ppm;
  return j;
}

RejectedInterval IntervalFromJson(const ParamReader& r) {
  RejectedInterval out;
  out.step = static_cast<int>(r.Integer("step", 0, INT32_MAX));
  out.t_start_s = r.Number("t_start_s", -1e12, 1e12, "s");
  out.t_end_s = r.Number("t_end_s", -1e12, 1e12, "s");
  if (!(out.t_end_s >= out.t_start_s)) {
    r.Fail(r.path(),
           "t_end_s " + std::to_string(out.t_end_s) + " is before t_start_s " +
               std::to_string(out.t_start_s));
  }
  out.reason = r.String("reason");
  return out;
}

// The format version, read wide so 4294967298 is refused as itself instead of wrapping to 2.
int FormatVersion(const json& meta, const std::string& source) {
  if (!meta.is_object() || !meta.contains("format_version")) {
    throw RecordingError(source + ": $.format_version missing");
  }
  const json& v = meta["format_version"];
  if (!v.is_number_integer()) {
    throw RecordingError(source + ": $.format_version is " + v.dump() + ", not an integer");
  }
  const int64_t version =
      v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX)
          ? INT64_MAX
          : v.get<int64_t>();
  if (version < INT32_MIN || version > INT32_MAX) {
    throw RecordingError(source + ": $.format_version is " + v.dump() + ", out of range");
  }
  return static_cast<int>(version);
}

// A unit listed twice would have its rows read twice by any consumer that walks the list.
void RefuseRepeatedUnits(const std::vector<RecordingUnit>& units, const std::string& source) {
  for (size_t i = 0; i < units.size(); ++i) {
    if (units[i].serial.empty()) continue;
    for (size_t j = 0; j < i; ++j) {
      if (units[j].serial == units[i].serial) {
        throw RecordingError(source + ": $.units[" + std::to_string(i) + "].serial " +
                             json(units[i].serial).dump() + " is listed already as $.units[" +
                             std::to_string(j) + "]");
      }
    }
  }
}

// A rate written as the integer it is (100), as the executor has always written it.
json RateJson(double hz) {
  if (std::floor(hz) == hz && std::abs(hz) < 1e15) return static_cast<int64_t>(hz);
  return hz;
}

// The keys RecordingMeta holds as fields; the others go to `extra`.
constexpr const char* kTyped[] = {"format_version",
                                  "run_id",
                                  "started_utc",
                                  "status",
                                  "station",
                                  "sequence",
                                  "sequence_file",
                                  "time_base",
                                  "sample_rate_hz",
                                  "local_gravity_mps2",
                                  "units",
                                  "instruments",
                                  "rejected_intervals",
                                  "resumed_t_s"};

void ReadTyped(const json& meta, const ParamReader& r, RecordingMeta* m) {
  m->run_id = OptionalString(r, "run_id");
  m->started_utc = OptionalString(r, "started_utc");
  m->status = OptionalString(r, "status");
  for (auto [key, out] : {std::pair{"station", &m->station}, {"sequence", &m->sequence}}) {
    if (r.Has(key)) {
      r.Child(key);  // an object, or refused with its path
      *out = meta[key];
    }
  }
  m->sequence_file = OptionalString(r, "sequence_file");
  m->time_base = OptionalString(r, "time_base");
  m->sample_rate_hz = OptionalNumber(r, "sample_rate_hz", 1e6, "Hz");
  m->local_gravity_mps2 = OptionalNumber(r, "local_gravity_mps2", 1e3, "m/s^2");
  if (r.Has("units")) {
    m->has_units = true;
    const size_t n = r.ArrayLength("units", 0, 100000);
    for (size_t i = 0; i < n; ++i) m->units.push_back(UnitFromJson(r.Element("units", i, n)));
  }
  if (r.Has("instruments")) {
    const size_t n = r.ArrayLength("instruments", 0, 100000);
    m->instruments.emplace();
    for (size_t i = 0; i < n; ++i) {
      const ParamReader item = r.Element("instruments", i, n);
      m->instruments->push_back({OptionalString(item, "role").value_or(""),
                                 OptionalString(item, "model").value_or(""),
                                 OptionalString(item, "detail").value_or("")});
    }
  }
  if (r.Has("rejected_intervals")) {
    m->has_rejected_intervals = true;
    const size_t n = r.ArrayLength("rejected_intervals", 0, 10000000);
    for (size_t i = 0; i < n; ++i) {
      m->rejected_intervals.push_back(IntervalFromJson(r.Element("rejected_intervals", i, n)));
    }
  }
  if (r.Has("resumed_t_s")) {
    m->resumed_t_s.resize(r.ArrayLength("resumed_t_s", 0, 100000));
    r.NumberArray("resumed_t_s", 0.0, 1e12, "s", m->resumed_t_s);
    for (size_t i = 1; i < m->resumed_t_s.size(); ++i) {
      if (m->resumed_t_s[i] < m->resumed_t_s[i - 1]) {
        r.Fail(r.path() + ".resumed_t_s[" + std::to_string(i) + "]",
               "goes back from " + json(m->resumed_t_s[i - 1]).dump() + " s");
      }
    }
  }
}

}  // namespace

const RecordingUnit* RecordingMeta::Unit(const std::string& serial) const {
  for (const RecordingUnit& u : units) {
    if (u.serial == serial) return &u;
  }
  return nullptr;
}

RecordingMeta RecordingMeta::FromJson(const json& meta, const std::string& source) {
  RecordingMeta m;
  m.format_version = FormatVersion(meta, source);
  try {
    ReadTyped(meta, ParamReader(meta, source), &m);
  } catch (const common::ParamError& e) {
    throw RecordingError(e.what());
  }
  RefuseRepeatedUnits(m.units, source);
  for (auto it = meta.begin(); it != meta.end(); ++it) {
    if (std::find(std::begin(kTyped), std::end(kTyped), it.key()) == std::end(kTyped)) {
      m.extra[it.key()] = it.value();
    }
  }
  return m;
}

json RecordingMeta::ToJson() const {
  json j = extra.is_object() ? extra : json::object();
  j["format_version"] = format_version;
  if (run_id) j["run_id"] = *run_id;
  if (started_utc) j["started_utc"] = *started_utc;
  if (status) j["status"] = *status;
  if (station) j["station"] = *station;
  if (sequence) j["sequence"] = *sequence;
  if (sequence_file) j["sequence_file"] = *sequence_file;
  if (time_base) j["time_base"] = *time_base;
  if (sample_rate_hz) j["sample_rate_hz"] = RateJson(*sample_rate_hz);
  if (local_gravity_mps2) j["local_gravity_mps2"] = *local_gravity_mps2;
  if (has_units || !units.empty()) {
    j["units"] = json::array();
    for (const RecordingUnit& u : units) j["units"].push_back(UnitToJson(u));
  }
  if (instruments) {
    j["instruments"] = json::array();
    for (const RecordingInstrument& i : *instruments) {
      j["instruments"].push_back({{"role", i.role}, {"model", i.model}, {"detail", i.detail}});
    }
  }
  if (has_rejected_intervals || !rejected_intervals.empty()) {
    j["rejected_intervals"] = RejectedIntervalsJson(rejected_intervals);
  }
  if (!resumed_t_s.empty()) j["resumed_t_s"] = resumed_t_s;
  return j;
}

json RejectedIntervalsJson(const std::vector<RejectedInterval>& intervals) {
  json list = json::array();
  for (const RejectedInterval& r : intervals) {
    list.push_back({{"step", r.step},
                    {"t_start_s", r.t_start_s},
                    {"t_end_s", r.t_end_s},
                    {"reason", r.reason}});
  }
  return list;
}

}  // namespace adahrs::hil
