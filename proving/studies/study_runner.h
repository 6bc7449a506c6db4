// The units of a study's shard run on a pool of threads: each thread takes the next unit index,
// results land in unit index order, so they never depend on the thread that ran a unit.
#pragma once

#include <functional>
#include <vector>

#include "proving/studies/imu_study.h"

namespace adahrs::proving {

using StudyUnitRunner = std::function<StudyUnitResult(int unit_index)>;

/// Unit `index` of the study before it runs: serial SIM-<index + 1, 6 digits>, draw and noise
/// seeds derived from the study seed and the index, no outcome yet.
StudyUnitResult NewStudyUnit(const StudySettings& settings, int index);

/// Runs `run` for every index 0...settings.units-1 the shard holds, on `threads` threads (0: all
/// cores); rethrows the first exception a unit throws (the remaining units are not started).
std::vector<StudyUnitResult> RunStudyUnits(const StudySettings& settings,
                                           int threads,
                                           const StudyProgress& progress,
                                           const StudyUnitRunner& run);

}  // namespace adahrs::proving
