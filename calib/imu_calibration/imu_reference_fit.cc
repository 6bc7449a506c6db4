#include "calib/imu_calibration/imu_reference_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "calib/solvers/cross_axis_fit.h"
#include "calib/solvers/gyro_scale_fit.h"
#include "calib/solvers/sample_statistics.h"
#include "calib/solvers/six_position_fit.h"
#include "common/imu_layout.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

constexpr double kCrossAxisRate_dps = 150.0;  // CG's reference (thesis Eq. 28)

int UpAxisIndex(int orientation) { return orientation / 10 - 1; }
double UpSign(int orientation) { return orientation % 10 == 1 ? 1.0 : -1.0; }

fm::ImuCalibrationConstants Identity() {
  fm::ImuCalibrationConstants c;
  c.ca_mps2_per_g = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  c.cg = c.ca_mps2_per_g;
  for (int ch = 0; ch < 9; ++ch) c.thermal[ch].temp_sensor = common::kImuChannels[ch].thermometer;
  return c;
}

ThermalChannelDiagnostics ThermalDiagnostics(const ThermalDriftResult& r) {
  ThermalChannelDiagnostics d;
  d.bands = r.all.bands;
  d.samples = r.all.samples;
  d.residual_rms = r.all.residual_rms;
  d.temp_min_cnt = r.all.temp_min_cnt;
  d.temp_max_cnt = r.all.temp_max_cnt;
  d.hysteresis = r.hysteresis;
  d.hysteresis_at_temp_cnt = r.hysteresis_at_temp_cnt;
  if (r.up) d.up_ramp_k = r.up->k;
  if (r.down) d.down_ramp_k = r.down->k;
  d.ramp_note = r.ramp_note;
  return d;
}

}  // namespace

ChannelMeans MeansOf(const fm::ImuCalibrationConstants& constants,
                     fm::ImuCompensationMode mode,
                     const std::vector<ImuSample>& samples,
                     const std::string& context) {
  std::array<std::vector<double>, 9> columns;
  for (const ImuSample& s : samples) {
    const auto out = fm::ImuReference(constants, mode, s.raw);
    for (int i = 0; i < 9; ++i) columns[i].push_back(out[i]);
  }
  ChannelMeans m;
  m.count = static_cast<int>(samples.size());
  for (int i = 0; i < 9; ++i) {
    const SampleMean s = SummariseSamples(context + " " + common::kImuChannelNames[i], columns[i]);
    m.mean[i] = s.mean;
    m.standard_error[i] = s.standard_error;
  }
  return m;
}

namespace {

// Stage 1: each channel's drift, a quadratic in its TEMP count over the thermal profile's rows.
void FitThermalStage(const ImuUnitData& unit,
                     const std::string& who,
                     const ImuReferenceOptions& options,
                     ReferenceFitDiagnostics* diag,
                     ImuFitResult* result) {
  if (unit.thermal.empty()) {
    throw ImuInputError(who + ": no thermal_profile rows (give the thermal-calibration run)");
  }
  fm::ImuCalibrationConstants& c = result->constants;
  // One buffer for the nine channels: a fresh one per channel faulted its pages in afresh each
  // time (tens of MB per channel on a full thermal profile).
  std::vector<ThermalSample> samples;
  samples.reserve(unit.thermal.size());
  for (int ch = 0; ch < 9; ++ch) {
    samples.clear();
    for (size_t i = 0; i < unit.thermal.size(); ++i) {
      const ImuSample& s = unit.thermal[i];
      const double u = fm::ImuReference(c, fm::ImuCompensationMode::kRaw, s.raw)[ch];
      samples.push_back({static_cast<double>(s.raw.temp_cnt[common::kImuChannels[ch].thermometer]),
                         u,
                         unit.thermal_segment[i]});
    }
    const ThermalDriftResult r =
        FitThermalDrift(who + " thermal " + common::kImuChannelNames[ch], samples, options.thermal);
    // The reference method's drift is a quadratic: the cubic term is fixed at zero, not estimated.
    c.thermal[ch].k = {r.all.k[0], r.all.k[1], r.all.k[2], 0.0};
    c.thermal[ch].temp_min_cnt = r.all.temp_min_cnt;
    c.thermal[ch].temp_max_cnt = r.all.temp_max_cnt;
    result->standard_errors.thermal[ch].k = {
        r.all.k_se[0], r.all.k_se[1], r.all.k_se[2], std::numeric_limits<double>::quiet_NaN()};
    diag->thermal[common::kImuChannelNames[ch]] = ThermalDiagnostics(r);
  }
}

// Stage 2: six-position offsets and scales, the acquisitions pooled per orientation.
void FitSixPositionStage(const ImuUnitData& unit,
                         const std::string& who,
                         double g_local_mps2,
                         ReferenceFitDiagnostics* diag,
                         ImuFitResult* result) {
  fm::ImuCalibrationConstants& c = result->constants;
  std::map<int, std::vector<ImuSample>> by_orientation;
  for (const ImuAcquisition& a : unit.accel) {
    auto& pool = by_orientation[a.orientation];
    pool.insert(pool.end(), a.samples.begin(), a.samples.end());
  }
  std::vector<AccelOrientationMeans> six;
  for (const auto& [orientation, samples] : by_orientation) {
    const ChannelMeans m = MeansOf(c,
                                   fm::ImuCompensationMode::kThermal,
                                   samples,
                                   who + " orientation " + std::to_string(orientation));
    AccelOrientationMeans s;
    s.orientation = orientation;
    for (int ch = 0; ch < 6; ++ch) {
      s.t_duty[ch] = m.mean[ch];
      s.t_duty_se[ch] = m.standard_error[ch];
    }
    six.push_back(s);
  }
  const auto accel = FitSixPosition(six, g_local_mps2);
  for (int ch = 0; ch < 6; ++ch) {
    c.accel[ch] = accel[ch].fit;
    result->standard_errors.accel[ch] = {accel[ch].offset_se_duty, accel[ch].scale_se_duty_per_g};
    diag->accel.push_back({common::kImuChannelNames[ch],
                           accel[ch].inverse_scale_g_per_duty,
                           accel[ch].inverse_scale_se_g_per_duty});
  }
}

// Stage 3: each gyro's cubic over the rate steps about its axis.
void FitGyroStage(const ImuUnitData& unit,
                  const std::string& who,
                  ReferenceFitDiagnostics* diag,
                  ImuFitResult* result) {
  fm::ImuCalibrationConstants& c = result->constants;
  for (int g = 0; g < 3; ++g) {
    std::vector<GyroRateMean> steps;
    for (const ImuAcquisition& a : unit.gyro) {
      if (UpAxisIndex(a.orientation) != g) continue;
      const ChannelMeans m = MeansOf(c,
                                     fm::ImuCompensationMode::kThermal,
                                     a.samples,
                                     who + " gyro step " + std::to_string(a.step));
      steps.push_back({a.rate_dps * UpSign(a.orientation), m.mean[6 + g], m.standard_error[6 + g]});
    }
    const GyroScaleEstimate e = FitGyroScale(who + " " + common::kImuChannelNames[6 + g], steps);
    c.gyro[g] = e.fit;
    result->standard_errors.gyro[g] = {e.null_se_cnt, e.l_se};
    diag->gyro.push_back({common::kImuChannelNames[6 + g], e.rates, e.residual_rms_dps});
  }
}

// The sensor-calibrated means of one cross-axis acquisition: the accelerometers' (slots 0..2)
// at rest, or the gyros' (slots 3..5) scaled to the reference rate.
AxisStepMean CrossAxisMean(const fm::ImuCalibrationConstants& c,
                           const ImuAcquisition& a,
                           bool rate,
                           const std::string& context) {
  const ChannelMeans m = MeansOf(c, fm::ImuCompensationMode::kFullyCalibrated, a.samples, context);
  const double k = rate ? kCrossAxisRate_dps / a.rate_dps : 1.0;
  const int first = rate ? 3 : 0;
  AxisStepMean s{a.orientation, {}, {}};
  for (int i = 0; i < 3; ++i) {
    s.mean[i] = k * m.mean[first + i];
    s.standard_error[i] = k * m.standard_error[first + i];
  }
  return s;
}

// Stage 4: cross-axis on sensor-calibrated means (CA = CG = I gives Ca and Cg in slots 0..5),
// from the cross_axis step or else the six positions and the fastest rate steps.
void FitCrossAxisStage(const ImuUnitData& unit,
                       const std::string& who,
                       double g_local_mps2,
                       ReferenceFitDiagnostics* diag,
                       ImuFitResult* result) {
  fm::ImuCalibrationConstants& c = result->constants;
  const bool have_step = !unit.cross_axis.empty();
  const std::vector<ImuAcquisition>& rest_source = have_step ? unit.cross_axis : unit.accel;
  const std::vector<ImuAcquisition>& rate_source = have_step ? unit.cross_axis : unit.gyro;
  std::vector<AxisStepMean> accel_steps, gyro_steps;
  for (int orientation : {11, 21, 31}) {
    const ImuAcquisition* rest = nullptr;
    const ImuAcquisition* fast = nullptr;
    for (const ImuAcquisition& a : rest_source) {
      if (a.orientation == orientation && std::abs(a.rate_dps) < 1.0) rest = &a;
    }
    for (const ImuAcquisition& a : rate_source) {
      if (a.orientation == orientation && a.rate_dps > 1.0 &&
          (!fast || a.rate_dps > fast->rate_dps)) {
        fast = &a;
      }
    }
    if (rest) {
      accel_steps.push_back(
          CrossAxisMean(c, *rest, false, who + " cross-axis rest " + std::to_string(orientation)));
    }
    if (fast) {
      gyro_steps.push_back(
          CrossAxisMean(c, *fast, true, who + " cross-axis rate " + std::to_string(orientation)));
    }
  }
  const CrossAxisEstimate ca =
      FitCrossAxis(who + " accelerometer cross-axis", accel_steps, g_local_mps2);
  const CrossAxisEstimate cg =
      FitCrossAxis(who + " gyro cross-axis", gyro_steps, kCrossAxisRate_dps);
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c.ca_mps2_per_g[r][k] = ca.matrix(r, k);
      c.cg[r][k] = cg.matrix(r, k);
      result->standard_errors.ca_mps2_per_g[r][k] = ca.standard_error(r, k);
      result->standard_errors.cg[r][k] = cg.standard_error(r, k);
    }
  }
  diag->cross_axis = {have_step ? "cross_axis step" : "accel and gyro steps",
                      ca.condition_number,
                      cg.condition_number};
}

void ReportExclusions(const ImuUnitData& unit, ImuFitDiagnostics* diag) {
  diag->excluded_rows = static_cast<int64_t>(unit.exclusions.size());
  constexpr size_t kListed = 100;  // the count above is complete; the list names the first ones
  diag->exclusions.assign(
      unit.exclusions.begin(),
      unit.exclusions.begin() + static_cast<long>(std::min(kListed, unit.exclusions.size())));
  diag->rejected_interval_rows = unit.rejected_interval_rows;
}

// The staged process: `stage`'s predecessors from the base, the rest as Identity() left them.
void TakeEarlierStages(const ImuReferenceOptions& options,
                       const std::string& who,
                       ImuFitResult* result) {
  const ImuStage stage = *options.stage;
  if (stage == ImuStage::kThermal) return;
  if (!options.base) {
    throw ImuInputError(who + ": the " + std::string(ImuStageName(stage)) +
                        " stage needs the earlier stages' constants (a base constants file)");
  }
  const ImuStageBase& base = *options.base;
  result->constants.thermal = base.constants.thermal;
  result->standard_errors.thermal = base.standard_errors.thermal;
  if (stage == ImuStage::kCrossAxis) {
    result->constants.accel = base.constants.accel;
    result->constants.gyro = base.constants.gyro;
    result->standard_errors.accel = base.standard_errors.accel;
    result->standard_errors.gyro = base.standard_errors.gyro;
  }
}

// What the fit ran, for the diagnostics.
const char* StrategySteps(const std::optional<ImuStage>& stage) {
  if (!stage) return "thermal (order 2), six-position, gyro cubic, cross-axis";
  switch (*stage) {
    case ImuStage::kThermal:
      return "thermal (order 2) stage alone";
    case ImuStage::kSensor:
      return "six-position and gyro cubic stage on the base's thermal constants";
    case ImuStage::kCrossAxis:
      return "cross-axis stage on the base's thermal and sensor constants";
  }
  return "";
}

}  // namespace

ImuFitResult FitImuReference(const ImuUnitData& unit,
                             double g_local_mps2,
                             const ImuReferenceOptions& options) {
  const std::string who = "unit " + unit.serial;
  ImuFitResult result;
  result.standard_errors = NotEstimated();
  result.constants = Identity();
  ReferenceFitDiagnostics& diag = result.diagnostics.reference.emplace();
  const auto runs = [&](ImuStage s) { return !options.stage || *options.stage == s; };
  if (options.stage) TakeEarlierStages(options, who, &result);
  if (runs(ImuStage::kThermal)) FitThermalStage(unit, who, options, &diag, &result);
  if (runs(ImuStage::kSensor)) {
    FitSixPositionStage(unit, who, g_local_mps2, &diag, &result);
    FitGyroStage(unit, who, &diag, &result);
  }
  if (runs(ImuStage::kCrossAxis)) FitCrossAxisStage(unit, who, g_local_mps2, &diag, &result);
  diag.strategy_steps = StrategySteps(options.stage);
  ReportExclusions(unit, &result.diagnostics);
  return result;
}

}  // namespace adahrs::calib
