// The check of a recording's sample times (docs/recording-format.md "Sample time"): a row whose
// sample time t_sample_s lies farther from its arrival time t_s than its unit's line can buffer
// is a recording defect (its frame count slipped by whole counter turns, or it waited longer than
// its line can hold). Two rows' waits differ by at most the unit's line_buffering_s from
// meta.json, widened by its clock_drift_ppm over the time since the unit's first row of the
// session, plus the 10 ms of one frame: every session (the run's start, each resume
// $.resumed_t_s) holds a unit's offsets to within that bound of the session's first row's offset.
// The first count is right only modulo the phase of the unit's counter turn against the run's
// clock (anywhere on a real line; after a resume, the frames the units ran unheard), so the
// absolute offset is not judged here (on a lockstep rig the sample clock test holds it against
// the rig's own packet log). Units whose line meta.json does not state are not checked.
// SampleTimeCheck collects, per unit and file, the rows outside with the first and the worst.
// Left out: which count would have been right (a defect says where, not how much).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hil/recording/recording_meta.h"

namespace adahrs::hil {

/// One unit's rows outside their bound, in one file.
struct SampleTimeDefect {
  std::string file;
  std::string unit;
  double bound_s = 0.0;         ///< the unit's line buffering + one frame, without drift
  int64_t rows = 0;             ///< its rows outside the bound
  int first_line = 0;           ///< the first of them, 1-based line of the file
  double first_offset_s = 0.0;  ///< its t_sample_s - t_s
  int worst_line = 0;           ///< the one farthest outside
  double worst_offset_s = 0.0;
  double worst_excess_s = 0.0;  ///< how far outside, s
  std::string Describe() const;
};

class SampleTimeCheck {
 public:
  SampleTimeCheck(const RecordingMeta& meta, std::filesystem::path file);

  /// Checks the row of `unit` at 1-based `line` with frame `frame` that arrived at `t_s`. Rows of
  /// a unit come in arrival order.
  void Row(const std::string& unit, int64_t frame, double t_s, int line);

  /// The units with rows outside their bound, in serial order.
  std::vector<SampleTimeDefect> Defects() const;

 private:
  struct Unit {
    double buffering_s = 0.0;
    double drift_ppm = 0.0;
    size_t session = 0;        // resumes before the unit's last row
    bool started = false;      // a row of this session seen
    double session_t_s = 0.0;  // the session's first row: arrival
    double reference_s = 0.0;  // and its offset, the one the session's rows are held to
    SampleTimeDefect defect;
  };
  std::vector<double> resumed_t_s_;
  std::filesystem::path file_;
  std::map<std::string, Unit, std::less<>> units_;
};

}  // namespace adahrs::hil
