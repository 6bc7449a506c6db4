// ReadAcceptanceFile (acceptance_file.h): acceptance.json into an AcceptanceFile through the
// strict parameter reader, every refusal with the file and the JSON path of the offending value.
#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "common/param_reader.h"

namespace adahrs::calib {
namespace {

using common::ParamReader;

constexpr double kAny = std::numeric_limits<double>::max();

double Number(const ParamReader& r, const char* key) { return r.Number(key, -kAny, kAny, ""); }
int Int(const ParamReader& r, const char* key) {
  return static_cast<int>(r.Integer(key, INT32_MIN, INT32_MAX));
}
std::optional<double> OptionalNumber(const ParamReader& r, const char* key) {
  return r.Has(key) ? std::optional<double>(Number(r, key)) : std::nullopt;
}

AcceptancePoint PointFrom(const ParamReader& r, int format_version) {
  AcceptancePoint p;
  p.step = Int(r, "step");
  p.kind = r.String("kind");
  p.quantity = r.String("quantity");
  p.unit = r.String("unit");
  (void)r.String("condition");  // written from the fields below; checked for its type only
  p.orientation = r.Has("orientation") ? Int(r, "orientation") : 0;
  p.rate_dps = OptionalNumber(r, "rate_dps");
  p.alt_ft = OptionalNumber(r, "alt_ft");
  p.cas_kt = OptionalNumber(r, "cas_kt");
  p.chamber_c = Number(r, "chamber_c");
  p.chamber_min_c = OptionalNumber(r, "chamber_min_c");
  p.chamber_max_c = OptionalNumber(r, "chamber_max_c");
  p.samples = r.Has("samples") ? Int(r, "samples") : 0;
  p.measured = Number(r, "measured");
  p.reference = Number(r, "reference");
  p.error = Number(r, "error");
  p.std_error = Number(r, "std_error");
  p.duration_s = OptionalNumber(r, "duration_s").value_or(0.0);
  p.noise = OptionalNumber(r, "noise").value_or(p.std_error);  // version 1 had no noise
  p.tolerance = Number(r, "tolerance");
  p.physical_limit = OptionalNumber(r, "physical_limit");
  p.pass = r.Flag("pass");
  p.beyond_noise = r.Has("beyond_noise") && r.Flag("beyond_noise");
  if (format_version >= 3) {  // before 3: no band, PASS or FAIL only
    p.marginal_band = r.Number("marginal_band_fraction", 0.0, 1.0, "");
    const std::string outcome = r.String("outcome");
    if (outcome != OutcomeText(p.outcome())) {
      r.Fail(r.path() + ".outcome",
             fmt::format("\"{}\" disagrees with the point's error, tolerance and band ({})",
                         outcome,
                         OutcomeText(p.outcome())));
    }
  }
  return p;
}

AcceptanceFileLimit LimitFrom(const ParamReader& r) {
  const ParamReader rest = r.Child("rest_record");
  return {Number(r, "since_calibration_h"), Number(rest, "record_s"), Number(rest, "chamber_c")};
}

void CheckFormat(const ParamReader& r, AcceptanceFile& out) {
  const std::string format = r.String("format");
  if (format != kAcceptanceFormatName) {
    r.Fail("$.format", fmt::format("expected \"{}\", got \"{}\"", kAcceptanceFormatName, format));
  }
  out.format_version = Int(r, "format_version");
  if (out.format_version < 1 || out.format_version > kAcceptanceFormatVersion) {
    r.Fail("$.format_version",
           fmt::format("{} is not 1...{}", out.format_version, kAcceptanceFormatVersion));
  }
}

// The verdict and failure count the file states must be those its points give.
void CheckStatedVerdict(const ParamReader& r, const UnitAcceptance& unit, int format_version) {
  const std::string verdict = r.String("verdict");
  if (verdict != "pass" && verdict != "fail") {
    r.Fail("$.verdict", "expected \"pass\" or \"fail\", got \"" + verdict + "\"");
  }
  const int stated_failed = r.Has("points_failed") ? Int(r, "points_failed") : unit.failed();
  if (stated_failed != unit.failed() || (verdict == "pass") != unit.pass()) {
    r.Fail("$.verdict",
           fmt::format("\"{}\" with points_failed {} disagrees with its points ({} of {} fail)",
                       verdict,
                       stated_failed,
                       unit.failed(),
                       unit.points.size()));
  }
  if (format_version < 3) return;
  const std::string outcome = r.String("outcome");
  const int stated_marginal = Int(r, "points_marginal");
  if (outcome != OutcomeText(unit.outcome()) || stated_marginal != unit.marginal()) {
    r.Fail("$.outcome",
           fmt::format("\"{}\" with points_marginal {} disagrees with its points ({}, {} marginal)",
                       outcome,
                       stated_marginal,
                       OutcomeText(unit.outcome()),
                       unit.marginal()));
  }
}

AcceptanceFileSpecification SpecificationIdFrom(const ParamReader& r) {
  const ParamReader spec = r.Child("specification");
  const std::string sha256 = spec.String("sha256");
  if (sha256.size() != 64 || sha256.find_first_not_of("0123456789abcdef") != std::string::npos) {
    spec.Fail("$.specification.sha256", "expected 64 lowercase hex digits");
  }
  return {spec.String("name"), spec.String("version"), sha256};
}

AcceptanceFile Read(const nlohmann::json& j, const ParamReader& r) {
  AcceptanceFile out;
  CheckFormat(r, out);
  out.unit.serial = r.String("serial");
  out.unit.kind = r.String("kind");
  out.unit.mode = r.Has("mode") ? Int(r, "mode") : 0;
  out.software_version = r.Has("software_version") ? r.String("software_version") : "";
  const ParamReader run = r.Child("run");
  out.run = {run.Has("dir") ? run.String("dir") : "",
             run.String("run_id"),
             run.Has("sequence") ? run.String("sequence") : "",
             run.String("recording_sha256")};
  const size_t n = r.ArrayLength("points", 0, SIZE_MAX);
  for (size_t i = 0; i < n; ++i) {
    out.unit.points.push_back(PointFrom(r.Element("points", i, n), out.format_version));
  }
  CheckStatedVerdict(r, out.unit, out.format_version);
  if (out.format_version >= 3) out.specification_id = SpecificationIdFrom(r);
  if (j.contains("physical_limit") && !j["physical_limit"].is_null()) {
    out.physical_limit = LimitFrom(r.Child("physical_limit"));  // null: no rest record
  }
  out.specification = j.value("specification", nlohmann::json());
  return out;
}

}  // namespace

AcceptanceFile ReadAcceptanceFile(const std::filesystem::path& file) {
  try {
    const nlohmann::json j = ParamReader::LoadFile(file.string());
    AcceptanceFile out = Read(j, ParamReader(j, file.string()));
    out.source = file;
    return out;
  } catch (const common::ParamError& e) {
    throw AcceptanceFileError(e.what());
  }
}

}  // namespace adahrs::calib
