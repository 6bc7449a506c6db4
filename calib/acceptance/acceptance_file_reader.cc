// ReadAcceptanceFile (acceptance_file.h): acceptance.json into an AcceptanceFile, every refusal
// with the file and the JSON path of the offending value.
#include <fstream>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

// One object of the file being read: typed fields by key, every refusal naming file and path.
class FileObject {
 public:
  FileObject(const json& object, std::string path, std::string source)
      : object_(object), path_(std::move(path)), source_(std::move(source)) {
    if (!object_.is_object()) Refuse(path_, "expected an object, got " + object_.dump());
  }
  std::string Path(const char* key) const { return path_ + "." + key; }
  bool Has(const char* key) const { return object_.contains(key) && !object_[key].is_null(); }

  const json& Get(const char* key) const {
    if (!object_.contains(key)) Refuse(Path(key), "missing");
    return object_[key];
  }
  std::string String(const char* key) const {
    const json& v = Get(key);
    if (!v.is_string()) Refuse(Path(key), "expected a string, got " + v.dump());
    return v.get<std::string>();
  }
  double Number(const char* key) const {
    const json& v = Get(key);
    if (!v.is_number()) Refuse(Path(key), "expected a number, got " + v.dump());
    return v.get<double>();
  }
  int Integer(const char* key) const {
    const json& v = Get(key);
    if (!v.is_number_integer() || v.get<int64_t>() < INT32_MIN || v.get<int64_t>() > INT32_MAX) {
      Refuse(Path(key), "expected an integer, got " + v.dump());
    }
    return v.get<int>();
  }
  bool Boolean(const char* key) const {
    const json& v = Get(key);
    if (!v.is_boolean()) Refuse(Path(key), "expected a boolean, got " + v.dump());
    return v.get<bool>();
  }
  const json& Array(const char* key) const {
    const json& v = Get(key);
    if (!v.is_array()) Refuse(Path(key), "expected an array, got " + v.dump());
    return v;
  }
  std::optional<double> OptionalNumber(const char* key) const {
    return Has(key) ? std::optional<double>(Number(key)) : std::nullopt;
  }
  FileObject Object(const char* key) const { return FileObject(Get(key), Path(key), source_); }
  const json& Get() const { return object_; }

  [[noreturn]] void Refuse(const std::string& path, const std::string& why) const {
    throw AcceptanceFileError(fmt::format("{}: {}: {}", source_, path, why));
  }

 private:
  const json& object_;
  std::string path_;
  std::string source_;
};

AcceptanceFilePoint PointFrom(const FileObject& o) {
  AcceptanceFilePoint read;
  AcceptancePoint& p = read.point;
  p.step = o.Integer("step");
  p.kind = o.String("kind");
  p.quantity = o.String("quantity");
  p.unit = o.String("unit");
  p.orientation = o.Has("orientation") ? o.Integer("orientation") : 0;
  p.rate_dps = o.OptionalNumber("rate_dps");
  p.alt_ft = o.OptionalNumber("alt_ft");
  p.cas_kt = o.OptionalNumber("cas_kt");
  p.chamber_c = o.Number("chamber_c");
  p.samples = o.Has("samples") ? o.Integer("samples") : 0;
  p.measured = o.Number("measured");
  p.reference = o.Number("reference");
  p.error = o.Number("error");
  p.std_error = o.Number("std_error");
  p.duration_s = o.OptionalNumber("duration_s").value_or(0.0);
  p.noise = o.OptionalNumber("noise").value_or(p.std_error);
  p.tolerance = o.Number("tolerance");
  p.physical_limit = o.OptionalNumber("physical_limit");
  p.pass = o.Boolean("pass");
  p.beyond_noise = o.Has("beyond_noise") && o.Boolean("beyond_noise");
  read.condition = o.String("condition");
  read.verdict = o.Has("verdict") ? o.String("verdict") : PointVerdictText(p.verdict());
  return read;
}

WorstMargin WorstFrom(const FileObject& o) {
  return {o.String("quantity"),
          o.String("unit"),
          o.Number("margin"),
          o.Integer("step"),
          o.String("point")};
}

AcceptanceFileLimit LimitFrom(const FileObject& o) {
  const FileObject rest = o.Object("rest_record");
  return {o.Number("since_calibration_h"), rest.Number("record_s"), rest.Number("chamber_c")};
}

std::map<std::string, std::map<std::string, int>> VerdictsFrom(const FileObject& o) {
  std::map<std::string, std::map<std::string, int>> out;
  for (const auto& [family, counts] : o.Object("point_verdicts").Get().items()) {
    if (!counts.is_object()) {
      o.Refuse(o.Path("point_verdicts") + "." + family, "expected an object, got " + counts.dump());
    }
    for (const auto& [verdict, n] : counts.items()) {
      if (!n.is_number_integer() || n.get<int64_t>() < 0) {
        o.Refuse(o.Path("point_verdicts") + "." + family + "." + verdict,
                 "expected a count, got " + n.dump());
      }
      out[family][verdict] = n.get<int>();
    }
  }
  return out;
}

json ParseFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw AcceptanceFileError(file.string() + ": cannot open");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {  // a syntax error, or a number beyond double's range
    throw AcceptanceFileError(file.string() + ": not JSON: " + e.what());
  }
}

void CheckFormat(const FileObject& o, AcceptanceFile& out) {
  const std::string format = o.String("format");
  if (format != kAcceptanceFormatName) {
    o.Refuse("$.format", fmt::format("expected \"{}\", got \"{}\"", kAcceptanceFormatName, format));
  }
  out.format_version = o.Integer("format_version");
  if (out.format_version < 1 || out.format_version > kAcceptanceFormatVersion) {
    o.Refuse("$.format_version",
             fmt::format("{} is not 1...{}", out.format_version, kAcceptanceFormatVersion));
  }
}

}  // namespace

AcceptanceFile ReadAcceptanceFile(const std::filesystem::path& file) {
  const json j = ParseFile(file);
  const std::string source = file.string();
  const FileObject o(j, "$", source);
  AcceptanceFile out;
  out.source = file;
  CheckFormat(o, out);
  out.serial = o.String("serial");
  out.kind = o.String("kind");
  out.mode = o.Has("mode") ? o.Integer("mode") : 0;
  out.software_version = o.Has("software_version") ? o.String("software_version") : "";
  const FileObject run = o.Object("run");
  out.run = {run.Has("dir") ? run.String("dir") : "",
             run.String("run_id"),
             run.Has("sequence") ? run.String("sequence") : "",
             run.String("recording_sha256")};
  const std::string verdict = o.String("verdict");
  if (verdict != "pass" && verdict != "fail") {
    o.Refuse("$.verdict", "expected \"pass\" or \"fail\", got \"" + verdict + "\"");
  }
  out.pass = verdict == "pass";
  const json& points = o.Array("points");
  for (size_t i = 0; i < points.size(); ++i) {
    out.points.push_back(PointFrom(FileObject(points[i], fmt::format("$.points[{}]", i), source)));
  }
  int failed = 0;
  for (const AcceptanceFilePoint& p : out.points) failed += p.point.pass ? 0 : 1;
  out.points_failed = o.Has("points_failed") ? o.Integer("points_failed") : failed;
  if (out.points_failed != failed || out.pass != (failed == 0)) {
    o.Refuse("$.verdict",
             fmt::format("\"{}\" with points_failed {} disagrees with its points ({} "
                         "of {} fail)",
                         verdict,
                         out.points_failed,
                         failed,
                         out.points.size()));
  }
  if (o.Has("point_verdicts")) out.point_verdicts = VerdictsFrom(o);
  if (o.Has("physical_limit")) out.physical_limit = LimitFrom(o.Object("physical_limit"));
  if (o.Has("worst_margin")) {
    const json& worst = o.Array("worst_margin");
    for (size_t i = 0; i < worst.size(); ++i) {
      out.worst_margin.push_back(
          WorstFrom(FileObject(worst[i], fmt::format("$.worst_margin[{}]", i), source)));
    }
  }
  if (o.Has("specification")) out.specification = o.Get("specification");
  return out;
}

}  // namespace adahrs::calib
