// A Monte Carlo study of ADS calibration strategies (docs/studies.md "ADS studies"): each unit
// index k of 0...units-1 is drawn (AdsUnitParams::Draw, serial SIM-<k+1, 6 digits>, seed derived
// from the study seed and 2k, noise from 2k + 1), run in process through each strategy's sequence
// (AdsRunRecording), its calibration points selected as from a recording on disk
// (SelectAdsCalibrationPoints), fitted (FitAdsStrategy), exported to the firmware's fixed-point
// blocks and evaluated against its truth over the envelope grid under every history
// (EvaluateAdsConstants), and judged against the specification's altitude and airspeed tolerances
// (Specification::Reference(), the tables EvaluateAdsConstants judges with): "altitude" passes when
// every altitude grid point is within its tolerance under every history, "airspeed" likewise,
// "all" when both do; "no_history" (informative) when both are with the operators fresh.
// Strategies that share a sequence file share the simulated run; every strategy sees the same
// units and the same noise (a paired comparison). A unit's result depends only on the study seed
// and its index.
#pragma once

#include <vector>

#include "proving/studies/imu_study.h"
#include "proving/studies/study_definition.h"

namespace adahrs::proving {

/// Runs the shard's units of every strategy (all ADS) on `threads` threads (0: all cores); results
/// in unit index order. Throws what a simulation throws; fit and export failures are outcomes.
std::vector<StudyUnitResult> RunAdsStudy(const std::vector<StudyDefinition>& strategies,
                                         const StudySettings& settings,
                                         int threads,
                                         const StudyProgress& progress = {});

/// Unit `index` of the study alone (the work of one thread).
StudyUnitResult RunAdsStudyUnit(const std::vector<StudyDefinition>& strategies,
                                const StudySettings& settings,
                                int index);

}  // namespace adahrs::proving
