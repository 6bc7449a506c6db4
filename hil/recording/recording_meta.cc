#include "hil/recording/recording_meta.h"

#include <algorithm>
#include <cmath>

#include "hil/recording/recording_error.h"

namespace adahrs::hil {
namespace {

using nlohmann::json;

// One object of meta.json being read: typed fields by key, every refusal with its JSON path.
class MetaObject {
 public:
  MetaObject(const json& object, std::string where) : object_(object), where_(std::move(where)) {
    if (!object_.is_object()) throw RecordingError(where_ + " is not an object");
  }
  bool Has(const char* key) const { return object_.contains(key); }
  const json& Raw(const char* key) const { return object_.at(key); }
  std::string Path(const char* key) const { return where_ + "." + key; }

  std::optional<std::string> String(const char* key) const {
    if (!Has(key)) return std::nullopt;
    if (!object_[key].is_string()) throw RecordingError(Path(key) + " is not a string");
    return object_[key].get<std::string>();
  }
  std::optional<double> Number(const char* key) const {
    if (!Has(key)) return std::nullopt;
    if (!object_[key].is_number()) throw RecordingError(Path(key) + " is not a number");
    return object_[key].get<double>();
  }
  std::optional<int64_t> Integer(const char* key) const {
    if (!Has(key)) return std::nullopt;
    const json& v = object_[key];
    if (!v.is_number_integer() ||
        (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX))) {
      throw RecordingError(Path(key) + " is " + v.dump() + ", not an integer");
    }
    return v.get<int64_t>();
  }
  const json& Array(const char* key) const {
    if (!object_[key].is_array()) throw RecordingError(Path(key) + " is not an array");
    return object_[key];
  }

 private:
  const json& object_;
  std::string where_;
};

RecordingUnit UnitFromJson(const json& item, const std::string& where) {
  const MetaObject o(item, where);
  RecordingUnit u;
  u.role = o.String("role").value_or("");
  u.kind = o.String("kind").value_or("");
  u.serial = o.String("serial").value_or("");
  u.serial_number = o.Integer("serial_number");
  u.firmware = o.String("firmware");
  u.slot = o.Integer("slot");
  u.constants_version = o.Integer("constants_version");
  u.mode = o.Integer("mode");
  return u;
}

json UnitToJson(const RecordingUnit& u) {
  json j = json::object();
  if (!u.role.empty()) j["role"] = u.role;
  if (!u.kind.empty()) j["kind"] = u.kind;
  if (!u.serial.empty()) j["serial"] = u.serial;
  if (u.serial_number) j["serial_number"] = *u.serial_number;
  if (u.firmware) j["firmware"] = *u.firmware;
  if (u.slot) j["slot"] = *u.slot;
  if (u.constants_version) j["constants_version"] = *u.constants_version;
  if (u.mode) j["mode"] = *u.mode;
  return j;
}

RejectedInterval IntervalFromJson(const json& item, const std::string& where) {
  const MetaObject o(item, where);
  RejectedInterval r;
  if (!o.Has("step") || !item["step"].is_number_integer()) {
    throw RecordingError(where + ".step missing or not an integer");
  }
  r.step = item["step"].get<int>();
  for (auto [key, out] : {std::pair{"t_start_s", &r.t_start_s}, {"t_end_s", &r.t_end_s}}) {
    if (!o.Has(key) || !item[key].is_number()) {
      throw RecordingError(where + "." + key + " missing or not a number");
    }
    *out = item[key].get<double>();
  }
  if (!(r.t_end_s >= r.t_start_s)) {
    throw RecordingError(where + ": t_end_s " + std::to_string(r.t_end_s) +
                         " is before t_start_s " + std::to_string(r.t_start_s));
  }
  if (!o.Has("reason") || !item["reason"].is_string()) {
    throw RecordingError(where + ".reason missing or not a string");
  }
  r.reason = item["reason"].get<std::string>();
  return r;
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
  const MetaObject o(meta, source + ": $");
  m.run_id = o.String("run_id");
  m.started_utc = o.String("started_utc");
  m.status = o.String("status");
  if (o.Has("station")) m.station = meta["station"];
  if (o.Has("sequence")) m.sequence = meta["sequence"];
  m.sequence_file = o.String("sequence_file");
  m.time_base = o.String("time_base");
  m.sample_rate_hz = o.Number("sample_rate_hz");
  m.local_gravity_mps2 = o.Number("local_gravity_mps2");
  if (o.Has("units")) {
    m.has_units = true;
    const json& units = o.Array("units");
    for (size_t i = 0; i < units.size(); ++i) {
      m.units.push_back(UnitFromJson(units[i], source + ": $.units[" + std::to_string(i) + "]"));
    }
    RefuseRepeatedUnits(m.units, source);
  }
  if (o.Has("instruments")) {
    const json& list = o.Array("instruments");
    m.instruments.emplace();
    for (size_t i = 0; i < list.size(); ++i) {
      const MetaObject item(list[i], source + ": $.instruments[" + std::to_string(i) + "]");
      m.instruments->push_back({item.String("role").value_or(""),
                                item.String("model").value_or(""),
                                item.String("detail").value_or("")});
    }
  }
  if (o.Has("rejected_intervals")) {
    m.has_rejected_intervals = true;
    const json& list = o.Array("rejected_intervals");
    for (size_t i = 0; i < list.size(); ++i) {
      m.rejected_intervals.push_back(
          IntervalFromJson(list[i], source + ": $.rejected_intervals[" + std::to_string(i) + "]"));
    }
  }
  static const char* const kTyped[] = {"format_version",
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
                                       "rejected_intervals"};
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
