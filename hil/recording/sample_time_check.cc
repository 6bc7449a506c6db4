#include "hil/recording/sample_time_check.h"

#include <cmath>

#include <fmt/format.h>

#include "hil/recording/frame_count.h"

namespace adahrs::hil {

std::string SampleTimeDefect::Describe() const {
  return fmt::format(
      "{}: unit {}: {} row(s) with t_sample_s - t_s beyond the line's bound of {:.3f} s: the "
      "first at line {} ({:+.3f} s), the worst at line {} ({:+.3f} s, {:.3f} s beyond)",
      file,
      unit,
      rows,
      bound_s,
      first_line,
      first_offset_s,
      worst_line,
      worst_offset_s,
      worst_excess_s);
}

SampleTimeCheck::SampleTimeCheck(const RecordingMeta& meta, std::filesystem::path file)
    : resumed_t_s_(meta.resumed_t_s), file_(std::move(file)) {
  for (const RecordingUnit& u : meta.units) {
    if (u.serial.empty() || !u.line_buffering_s) continue;
    Unit& unit = units_[u.serial];
    unit.buffering_s = *u.line_buffering_s;
    unit.drift_ppm = u.clock_drift_ppm.value_or(0.0);
  }
}

void SampleTimeCheck::Row(const std::string& unit, int64_t frame, double t_s, int line) {
  auto it = units_.find(unit);
  if (it == units_.end()) return;
  Unit& u = it->second;
  size_t session = u.session;
  while (session < resumed_t_s_.size() && t_s >= resumed_t_s_[session]) ++session;
  const double offset_s = SampleTimeS(frame) - t_s;
  if (!u.started || session != u.session) {
    u.session_t_s = t_s;
    // Every session is held to its first row's offset: on a real line the counter's turns start
    // anywhere against the run's clock, so the first count is right only modulo a turn's phase.
    u.reference_s = offset_s;
    u.session = session;
    u.started = true;
  }
  const double bound_s = u.buffering_s + kUnitFramePeriod_s;
  const double allowed_s = bound_s + u.drift_ppm * 1e-6 * (t_s - u.session_t_s);
  const double excess_s = std::abs(offset_s - u.reference_s) - allowed_s;
  if (excess_s <= 0.0) return;
  SampleTimeDefect& d = u.defect;
  if (d.rows++ == 0) {
    d.file = file_.string();
    d.unit = unit;
    d.bound_s = bound_s;
    d.first_line = line;
    d.first_offset_s = offset_s;
  }
  if (excess_s > d.worst_excess_s) {
    d.worst_line = line;
    d.worst_offset_s = offset_s;
    d.worst_excess_s = excess_s;
  }
}

std::vector<SampleTimeDefect> SampleTimeCheck::Defects() const {
  std::vector<SampleTimeDefect> out;
  for (const auto& [serial, u] : units_) {
    if (u.defect.rows > 0) out.push_back(u.defect);
  }
  return out;
}

}  // namespace adahrs::hil
