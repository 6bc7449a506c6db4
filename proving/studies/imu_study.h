// A Monte Carlo study of IMU calibration strategies (docs/studies.md): each unit index k of
// 0...units-1 is drawn (ImuUnitParams::Draw, serial SIM-<k+1, 6 digits>, seed derived from the
// study seed and k), run in process through each strategy's sequence (ImuRunSimulator: soaks
// without frames, ramps at their written rate), fitted, exported to the firmware's blocks and
// evaluated against its truth over the envelope grid (EvaluateImu), and judged against the
// specification (Specification::Reference(): acceleration and body rate; "all" = both), and the
// body rate also against the limit the calibration's design allows (EvaluateImu's verdict).
// Strategies that share a sequence file share the simulated recording; every strategy sees the
// same units and the same noise (a paired comparison).
// Determinism: a unit's result depends only on the study seed and its index, never on the thread
// that ran it or on the shard (--shard i/n holds the indices k with k mod n = i - 1).
// ADS units: ads_study.h (the same settings, shard and unit results; its own outcome fields).
// Left out: station gravity other than the study's.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/gravity.h"
#include "proving/studies/study_definition.h"

namespace adahrs::proving {

/// A deterministic slice of the unit indices: shard `index` of `count` (1-based).
struct StudyShard {
  int index = 1;
  int count = 1;

  /// "i/n" with 1 <= i <= n; throws std::invalid_argument naming `field` and the rule broken.
  static StudyShard Parse(const std::string& spec, const std::string& field);
  bool Holds(int unit_index) const { return unit_index % count == index - 1; }
  std::string Label() const { return std::to_string(index) + "/" + std::to_string(count); }
};

struct StudySettings {
  int units = 100;
  uint64_t seed = 1;
  StudyPopulation population;
  StudyShard shard;
  /// The simulated station's gravity (the virtual rig's site,
  /// docs/examples/station-virtual-rig.json).
  double g_local_mps2 = common::NormalGravityMps2(34.7, 190.0);
  int evaluation_frames = 40;  ///< frames averaged per grid point by EvaluateImu
};

/// One strategy's outcome for one unit. A fit the data cannot determine, or constants the
/// firmware exporter refuses, are outcomes (fitted false, failure says why), judged failing.
struct StrategyOutcome {
  bool fitted = false;
  std::string failure;
  double worst_accel_mg = 0.0;
  double worst_rate_dps = 0.0;
  std::string accel_verdict;
  std::string rate_verdict;
  bool pass_acceleration = false;
  bool pass_body_rate = false;
  /// Body rate within the specification or within the limit the calibration design allows
  /// (EvaluateImu's verdicts "within 1.5x the physical limit" or "... the firmware floor plus the
  /// physical limit"); the reference strategy has no such limit. Informative: not part of "all".
  bool pass_body_rate_limit = false;
  bool pass_all() const { return pass_acceleration && pass_body_rate; }

  /// ADS studies (ads_study.h): the worst |error| / tolerance over the envelope grid under every
  /// history of EvaluateAdsConstants, and with the operators fresh; grid points failing (fail or
  /// unreachable).
  double worst_altitude_tol = 0.0;
  double worst_airspeed_tol = 0.0;
  double worst_altitude_no_history_tol = 0.0;
  double worst_airspeed_no_history_tol = 0.0;
  int altitude_failing_points = 0;
  int airspeed_failing_points = 0;
  bool pass_altitude = false;    ///< every altitude grid point within tolerance, every history
  bool pass_airspeed = false;    ///< every airspeed grid point within tolerance, every history
  bool pass_no_history = false;  ///< both within tolerance with fresh operators (informative)
  bool pass_ads_all() const { return pass_altitude && pass_airspeed; }
};

struct StudyUnitResult {
  int index = 0;
  std::string serial;
  uint64_t draw_seed = 0;
  uint64_t noise_seed = 0;
  std::vector<StrategyOutcome> outcomes;  ///< one per strategy, in the study's order
};

using StudyProgress = std::function<void(int units_done, int units_total)>;

/// Runs the shard's units of every strategy on `threads` threads (0: all cores); results in unit
/// index order. Throws what a simulation or evaluation throws other than the outcomes above.
std::vector<StudyUnitResult> RunImuStudy(const std::vector<StudyDefinition>& strategies,
                                         const StudySettings& settings,
                                         int threads,
                                         const StudyProgress& progress = {});

/// Unit `index` of the study alone (the work of one thread).
StudyUnitResult RunImuStudyUnit(const std::vector<StudyDefinition>& strategies,
                                const StudySettings& settings,
                                int index);

}  // namespace adahrs::proving
