#include "proving/studies/imu_study.h"

#include "proving/studies/study_runner.h"

#include <exception>
#include <limits>
#include <stdexcept>

#include "calib/acceptance/specification.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/solvers/linear_least_squares.h"
#include "proving/evaluation/imu_evaluation.h"
#include "proving/studies/imu_run_simulator.h"

namespace adahrs::proving {
namespace {

constexpr const char* kSoftwareVersion = "study";

// The unit's recording of `sequence`, collected as LoadImuRuns collects a recording on disk.
calib::ImuRunData Simulate(const StudyDefinition& d,
                           const sensor_sim::ImuUnitParams& params,
                           const StudySettings& settings,
                           uint64_t noise_seed) {
  calib::ImuRunData data;
  calib::ImuRunCollector collector("simulated " + d.sequence.name,
                                   "",
                                   d.sequence,
                                   settings.g_local_mps2,
                                   {params.serial},
                                   {},
                                   &data);
  ImuRunSimulator simulator({params}, settings.g_local_mps2, noise_seed);
  int line = 1;
  simulator.Run(d.sequence, [&](const hil::ImuRecordRow& row) { collector.Take(row, ++line); });
  collector.Finish();
  return data;
}

StrategyOutcome Judge(const StudyDefinition& d,
                      const calib::ImuRunData& data,
                      const sensor_sim::ImuUnitParams& params,
                      const StudySettings& settings) {
  StrategyOutcome o;
  const calib::Specification spec = calib::Specification::Reference();
  try {
    const calib::ConstantsFile constants =
        calib::FitImuUnit(data.units.at(params.serial), data, d.strategy, kSoftwareVersion);
    ImuEvaluationOptions options;
    options.g_local_mps2 = settings.g_local_mps2;
    options.frames = settings.evaluation_frames;
    const ImuEvaluation e = EvaluateImu(constants, params, spec, options);
    o.fitted = true;
    o.worst_accel_mg = e.worst_accel_mg;
    o.worst_rate_dps = e.worst_rate_dps;
    o.accel_verdict = e.accel_verdict;
    o.rate_verdict = e.rate_verdict;
    o.pass_acceleration = e.worst_accel_mg <= spec.accel_mg;
    o.pass_body_rate = e.worst_rate_dps <= spec.body_rate_dps;
    o.pass_body_rate_limit =
        o.pass_body_rate || (e.rate_verdict.find("within 1.5x") != std::string::npos);
  } catch (const calib::DegenerateDesignError& e) {
    o.failure = std::string("fit: ") + e.what();
  } catch (const ConstantsNotExportable& e) {
    o.failure = std::string("export: ") + e.what();
  }
  if (!o.fitted) {
    o.worst_accel_mg = o.worst_rate_dps = std::numeric_limits<double>::quiet_NaN();
  }
  return o;
}

}  // namespace

StudyShard StudyShard::Parse(const std::string& spec, const std::string& field) {
  const size_t slash = spec.find('/');
  StudyShard s;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no '/'");
    size_t used_i = 0, used_n = 0;
    s.index = std::stoi(spec.substr(0, slash), &used_i);
    s.count = std::stoi(spec.substr(slash + 1), &used_n);
    if (used_i != slash || used_n != spec.size() - slash - 1)
      throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw std::invalid_argument(field + " \"" + spec + "\": expected i/n, two whole numbers");
  }
  if (s.count < 1)
    throw std::invalid_argument(field + " \"" + spec + "\": the shard count n must be at least 1");
  if (s.index < 1 || s.index > s.count) {
    throw std::invalid_argument(field + " \"" + spec + "\": the shard index i must be 1..." +
                                std::to_string(s.count));
  }
  return s;
}

StudyUnitResult RunImuStudyUnit(const std::vector<StudyDefinition>& strategies,
                                const StudySettings& settings,
                                int index) {
  StudyUnitResult r = NewStudyUnit(settings, index);
  sensor_sim::ImuUnitParams params =
      sensor_sim::ImuUnitParams::Draw(r.serial, r.draw_seed, settings.population.profile);
  params.ApplyVariant(settings.population.variant);
  std::vector<std::pair<std::string, calib::ImuRunData>> runs;  // by sequence file, shared
  for (const StudyDefinition& d : strategies) {
    const calib::ImuRunData* data = nullptr;
    for (const auto& [file, run] : runs) {
      if (file == d.sequence_file) data = &run;
    }
    if (!data) {
      runs.emplace_back(d.sequence_file, Simulate(d, params, settings, r.noise_seed));
      data = &runs.back().second;
    }
    r.outcomes.push_back(Judge(d, *data, params, settings));
  }
  return r;
}

std::vector<StudyUnitResult> RunImuStudy(const std::vector<StudyDefinition>& strategies,
                                         const StudySettings& settings,
                                         int threads,
                                         const StudyProgress& progress) {
  return RunStudyUnits(settings, threads, progress, [&](int unit_index) {
    return RunImuStudyUnit(strategies, settings, unit_index);
  });
}

}  // namespace adahrs::proving
