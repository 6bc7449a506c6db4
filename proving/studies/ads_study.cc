#include "proving/studies/ads_study.h"

#include <limits>
#include <stdexcept>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/solvers/linear_least_squares.h"
#include "proving/evaluation/ads_evaluation.h"
#include "proving/studies/ads_run_simulator.h"
#include "proving/studies/study_runner.h"

namespace adahrs::proving {
namespace {

// The largest |error| / tolerance over the grid under every history.
double WorstRatioWithHistory(const AdsQuantityEvaluation& q) {
  double worst = 0.0;
  for (const AdsGridPoint& p : q.grid) worst = std::max(worst, p.worst_with_history / p.tolerance);
  return worst;
}

StrategyOutcome Judge(const StudyDefinition& d,
                      const std::vector<calib::AdsCalibrationPoint>& points,
                      const sensor_sim::AdsUnitParams& params) {
  StrategyOutcome o;
  try {
    const calib::AdsFitResult fit = calib::FitAdsStrategy(d.ads_strategy, params.serial, points);
    const AdsEvaluation e = EvaluateAdsConstants(fit.constants, params);
    o.fitted = true;
    o.worst_altitude_tol = WorstRatioWithHistory(e.altitude);
    o.worst_airspeed_tol = WorstRatioWithHistory(e.airspeed);
    o.worst_altitude_no_history_tol = e.altitude.worst_ratio_no_history;
    o.worst_airspeed_no_history_tol = e.airspeed.worst_ratio_no_history;
    o.altitude_failing_points = e.altitude.fail + e.altitude.unreachable;
    o.airspeed_failing_points = e.airspeed.fail + e.airspeed.unreachable;
    o.pass_altitude = o.altitude_failing_points == 0;
    o.pass_airspeed = o.airspeed_failing_points == 0;
    o.pass_no_history =
        o.worst_altitude_no_history_tol <= 1.0 && o.worst_airspeed_no_history_tol <= 1.0;
  } catch (const calib::DegenerateDesignError& e) {
    o.failure = std::string("fit: ") + e.what();
  } catch (const std::invalid_argument& e) {
    o.failure = std::string("export: ") + e.what();
  }
  if (!o.fitted) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    o.worst_altitude_tol = o.worst_airspeed_tol = nan;
    o.worst_altitude_no_history_tol = o.worst_airspeed_no_history_tol = nan;
  }
  return o;
}

}  // namespace

StudyUnitResult RunAdsStudyUnit(const std::vector<StudyDefinition>& strategies,
                                const StudySettings& settings,
                                int index) {
  StudyUnitResult r = NewStudyUnit(settings, index);
  sensor_sim::AdsUnitParams params =
      sensor_sim::AdsUnitParams::Draw(r.serial, r.draw_seed, settings.population.profile);
  params.ApplyVariant(settings.population.variant);
  std::vector<std::pair<std::string, std::vector<calib::AdsCalibrationPoint>>>
      runs;  // by sequence file
  for (const StudyDefinition& d : strategies) {
    const std::vector<calib::AdsCalibrationPoint>* points = nullptr;
    for (const auto& [file, run] : runs) {
      if (file == d.sequence_file) points = &run;
    }
    if (!points) {
      const hil::Recording recording = AdsRunRecording(d.sequence, params, r.noise_seed);
      runs.emplace_back(d.sequence_file,
                        calib::SelectAdsCalibrationPoints(
                            recording, params.serial, "simulated " + d.sequence.name));
      points = &runs.back().second;
    }
    r.outcomes.push_back(Judge(d, *points, params));
  }
  return r;
}

std::vector<StudyUnitResult> RunAdsStudy(const std::vector<StudyDefinition>& strategies,
                                         const StudySettings& settings,
                                         int threads,
                                         const StudyProgress& progress) {
  return RunStudyUnits(settings, threads, progress, [&](int index) {
    return RunAdsStudyUnit(strategies, settings, index);
  });
}

}  // namespace adahrs::proving
