#include "calib/records/unit_history_text.h"

#include <fmt/format.h>

namespace adahrs::calib {

std::string FormatUnitHistory(const UnitHistory& history) {
  std::string out = fmt::format(
      "{} ({}), first recorded {}\n", history.serial, history.kind, history.first_seen_utc);
  out += fmt::format("runs: {}\n", history.runs.size());
  for (const UnitRunEntry& run : history.runs) {
    out += fmt::format("  {}  {:<12} {:<34} {:<6} {}  recording sha256 {}\n",
                       run.started_utc,
                       run.status,
                       run.sequence_name,
                       run.role,
                       run.run_id,
                       run.recording_sha256.substr(0, 16));
  }
  out += fmt::format("constants versions: {}\n", history.constants.size());
  for (const ConstantsVersion& v : history.constants) {
    std::string state = v.downloads == 0 ? "not downloaded"
                        : v.committed
                            ? fmt::format("committed (unit constants version {}, crc 0x{:04X})",
                                          v.unit_constants_version.value_or(0),
                                          v.unit_constants_crc.value_or(0))
                            : fmt::format("{} download attempt(s), none committed", v.downloads);
    out += fmt::format("  v{}  {}  strategy {:<12} file sha256 {}  {}\n",
                       v.version,
                       v.created_utc,
                       v.strategy,
                       v.file_sha256.substr(0, 16),
                       state);
  }
  out += fmt::format("acceptance: {}\n", history.acceptance.size());
  for (const AcceptanceVerdict& a : history.acceptance) {
    const char* outcome = a.failed > 0 ? "FAIL" : a.marginal > 0 ? "MARGINAL" : "PASS";
    out += fmt::format("  {}  {}: {} of {} points within tolerance, {} marginal{}\n",
                       a.run_id,
                       outcome,
                       a.points - a.failed,
                       a.points,
                       a.marginal,
                       a.specification_sha256.empty()
                           ? ""
                           : "  specification sha256 " + a.specification_sha256.substr(0, 16));
    for (const AcceptancePointRecord& p : a.failures) {
      out += fmt::format("    FAIL {} at {}: error {:.6g} {} > tolerance {:.6g} {}\n",
                         p.quantity,
                         p.condition,
                         p.error,
                         p.unit,
                         p.tolerance,
                         p.unit);
    }
  }
  return out;
}

}  // namespace adahrs::calib
