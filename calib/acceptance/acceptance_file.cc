#include "calib/acceptance/acceptance_file.h"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

#include "common/atomic_file.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

json PointJson(const AcceptancePoint& p) {
  json j = {{"step", p.step}, {"kind", p.kind}, {"quantity", p.quantity}};
  if (p.orientation != 0) j["orientation"] = p.orientation;
  if (p.rate_dps) j["rate_dps"] = *p.rate_dps;
  if (p.alt_ft) j["alt_ft"] = *p.alt_ft;
  if (p.cas_kt) j["cas_kt"] = *p.cas_kt;
  j["chamber_c"] = p.chamber_c;
  if (p.chamber_min_c) j["chamber_min_c"] = *p.chamber_min_c;
  if (p.chamber_max_c) j["chamber_max_c"] = *p.chamber_max_c;
  j["condition"] = p.Condition();
  j["unit"] = p.unit;
  j["samples"] = p.samples;
  j["measured"] = p.measured;
  j["reference"] = p.reference;
  j["error"] = p.error;
  j["std_error"] = p.std_error;
  j["duration_s"] = p.duration_s;
  j["noise"] = p.noise;
  j["tolerance"] = p.tolerance;
  j["margin"] = p.margin();
  if (p.physical_limit) j["physical_limit"] = *p.physical_limit;
  j["marginal_band_fraction"] = p.marginal_band;
  j["pass"] = p.pass;
  j["outcome"] = OutcomeText(p.outcome());
  j["verdict"] = PointVerdictText(p.verdict());
  j["beyond_noise"] = p.beyond_noise;
  return j;
}

void WriteAtomically(const std::filesystem::path& out, const std::string& text) {
  try {
    common::WriteFileAtomically(out, text);
  } catch (const common::AtomicWriteError& e) {
    throw AcceptanceFileError(e.what());
  }
}

}  // namespace

json AcceptanceJson(const AcceptanceRun& run,
                    const UnitAcceptance& unit,
                    const Specification& spec,
                    const std::string& software_version) {
  json points = json::array();
  for (const AcceptancePoint& p : unit.points) points.push_back(PointJson(p));
  json worst = json::array();
  for (const WorstMargin& w : unit.WorstMargins()) {
    worst.push_back({{"quantity", w.quantity},
                     {"unit", w.unit},
                     {"margin", w.margin},
                     {"step", w.step},
                     {"point", w.point},
                     {"pass", w.margin >= 0.0}});
  }
  json reference = {
      {"accel", "orientation's up axis times local gravity, in g (1 g = 9.80665 m/s^2)"},
      {"rate", "table_rate_dps about the up axis, 0 about the others; Earth rate not added"},
      {"altitude", "ISA pressure altitude of ps_ref_pa"},
      {"airspeed", "calibrated airspeed of qc_ref_pa"}};
  if (unit.kind == "imu") reference["local_gravity_mps2"] = run.local_gravity_mps2;
  json verdicts = json::object();
  for (const std::string family : {"acceleration",
                                   "body_rate",
                                   "altitude",
                                   "airspeed",
                                   "thermal_acceleration_std",
                                   "thermal_body_rate_std"}) {
    json counts = json::object();
    for (PointVerdict v : {PointVerdict::kWithinSpecification,
                           PointVerdict::kWithinPhysicalLimit,
                           PointVerdict::kOutsideBoth,
                           PointVerdict::kOutsideSpecification}) {
      if (const int n = unit.Count(family, v); n > 0) counts[PointVerdictText(v)] = n;
    }
    if (!counts.empty()) verdicts[family] = counts;
  }
  json physical_limit = nullptr;
  if (unit.rest) {
    physical_limit = {{"since_calibration_h", run.since_calibration_h},
                      {"rest_record", unit.rest->ToJson()},
                      {"law",
                       "3 sqrt(sigma_point^2 + 2 B2(T/tau) sigma_floor^2), flicker floor "
                       "from the rest record's Allan deviation"}};
  }
  return {{"format", kAcceptanceFormatName},
          {"format_version", kAcceptanceFormatVersion},
          {"serial", unit.serial},
          {"kind", unit.kind},
          {"mode", unit.mode},
          {"software_version", software_version},
          {"run",
           {{"dir", run.run_dir},
            {"run_id", run.run_id},
            {"sequence", run.sequence_name},
            {"recording_sha256", run.recording_sha256}}},
          {"specification", spec.ToJson()},
          {"reference", reference},
          {"verdict", unit.pass() ? "pass" : "fail"},
          {"outcome", OutcomeText(unit.outcome())},
          {"points_total", unit.points.size()},
          {"points_failed", unit.failed()},
          {"points_marginal", unit.marginal()},
          {"point_verdicts", verdicts},
          {"physical_limit", physical_limit},
          {"worst_margin", worst},
          {"points", points}};
}

std::vector<std::filesystem::path> WriteAcceptanceFiles(const AcceptanceRun& run,
                                                        const Specification& spec,
                                                        const std::string& software_version,
                                                        const std::filesystem::path& out_dir) {
  std::vector<std::filesystem::path> paths;
  for (const UnitAcceptance& unit : run.units) {
    const std::filesystem::path dir = out_dir / unit.serial;
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / kAcceptanceFileName;
    WriteAtomically(file, AcceptanceJson(run, unit, spec, software_version).dump(2) + "\n");
    paths.push_back(file);
  }
  return paths;
}

std::vector<std::filesystem::path> FindAcceptanceFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::filesystem::path file = entry.path() / kAcceptanceFileName;
    if (entry.is_directory() && std::filesystem::is_regular_file(file)) files.push_back(file);
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string RateVerdictLine(const UnitAcceptance& unit) {
  const auto count = [&](PointVerdict v) { return unit.Count("body_rate", v); };
  const int total = count(PointVerdict::kWithinSpecification) +
                    count(PointVerdict::kWithinPhysicalLimit) + count(PointVerdict::kOutsideBoth) +
                    count(PointVerdict::kOutsideSpecification);
  if (total == 0) return "";
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (const AcceptancePoint& p : unit.points) {
    if (QuantityFamily(p.quantity) != "body_rate" || !p.physical_limit) continue;
    lo = any ? std::min(lo, *p.physical_limit) : *p.physical_limit;
    hi = any ? std::max(hi, *p.physical_limit) : *p.physical_limit;
    any = true;
  }
  std::string line = fmt::format("body-rate points: {} of {} {}",
                                 count(PointVerdict::kWithinSpecification),
                                 total,
                                 PointVerdictText(PointVerdict::kWithinSpecification));
  if (any) {
    line += fmt::format(", {} {}, {} {} (physical limit {:.3g}...{:.3g} deg/s)",
                        count(PointVerdict::kWithinPhysicalLimit),
                        PointVerdictText(PointVerdict::kWithinPhysicalLimit),
                        count(PointVerdict::kOutsideBoth),
                        PointVerdictText(PointVerdict::kOutsideBoth),
                        lo,
                        hi);
  } else {
    line += fmt::format(", {} {} (no rest record: no physical limit)",
                        count(PointVerdict::kOutsideSpecification),
                        PointVerdictText(PointVerdict::kOutsideSpecification));
  }
  return line + "\n";
}

std::string AcceptanceText(const AcceptanceRun& run) {
  std::string out = fmt::format(
      "acceptance of run {} ({}), sequence {}\n", run.run_id, run.run_dir, run.sequence_name);
  for (const UnitAcceptance& unit : run.units) {
    out += fmt::format("\n{} ({}, mode {})\n", unit.serial, unit.kind, unit.mode);
    out += fmt::format("{:>4} {:<15} {:<9} {:<38} {:>12} {:>10} {:>10} {:>9} {:>9} {:<5} {}\n",
                       "step",
                       "kind",
                       "quantity",
                       "condition",
                       "measured",
                       "error",
                       "noise",
                       "tol",
                       "phys lim",
                       "unit",
                       "verdict");
    for (const AcceptancePoint& p : unit.points) {
      out += fmt::format(
          "{:>4} {:<15} {:<9} {:<38} {:>12.4f} {:>10.4f} {:>10.4f} {:>9.4f} {:>9} {:<5} {}{}{}\n",
          p.step,
          p.kind,
          p.quantity,
          p.Condition(),
          p.measured,
          p.error,
          p.noise,
          p.tolerance,
          p.physical_limit ? fmt::format("{:.4f}", *p.physical_limit) : "-",
          p.unit,
          OutcomeText(p.outcome()),
          p.pass ? "" : std::string(" (") + PointVerdictText(p.verdict()) + ")",
          p.beyond_noise ? "" : " (within noise of the tolerance)");
    }
    for (const WorstMargin& w : unit.WorstMargins()) {
      out += fmt::format("worst {} margin {:.4f} {} (step {}, {})\n",
                         w.quantity,
                         w.margin,
                         w.unit,
                         w.step,
                         w.point);
    }
    out += RateVerdictLine(unit);
    out += fmt::format("{}: {} ({} of {} points failed, {} marginal)\n",
                       unit.serial,
                       OutcomeText(unit.outcome()),
                       unit.failed(),
                       unit.points.size(),
                       unit.marginal());
  }
  return out;
}

}  // namespace adahrs::calib
