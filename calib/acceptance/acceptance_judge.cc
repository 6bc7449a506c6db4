#include "calib/acceptance/acceptance_judge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "calib/constants/recording_checksum.h"
#include "calib/sequence/sequence_json.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "common/units.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

constexpr double kRateMatch_dps = 1.0;  // a reported rate belongs to the command within this
constexpr double kMgPerG = 1000.0;
constexpr double kDefaultSampleRate_hz = 100.0;  // the units' frame rate when meta.json omits it
constexpr const char* kAxisNames[3] = {"x", "y", "z"};

// Where an error happened: run, unit, step and its kind and TAG.
struct Where {
  std::string run;
  std::string serial;
  int step = 0;
  std::string kind;
  int tag = 0;
  std::string Text() const {
    return fmt::format("run {}: unit {}: step {} ({}, tag {})", run, serial, step, kind, tag);
  }
};

[[noreturn]] void Refuse(const Where& where, const std::string& message) {
  throw AcceptanceInputError(where.Text() + ": " + message);
}

// Running mean and standard error of per-packet values.
struct Moments {
  double sum = 0.0;
  double sum_sq = 0.0;
  int n = 0;
  void Add(double v) {
    sum += v;
    sum_sq += v * v;
    ++n;
  }
  double Mean() const { return sum / n; }
  double Std() const {
    if (n < 2) return 0.0;
    const double mean = Mean();
    return std::sqrt(std::max(0.0, (sum_sq - n * mean * mean) / (n - 1)));
  }
  double StdError() const { return n < 2 ? 0.0 : Std() / std::sqrt(n); }
};

// Per-packet measured and reference values of one quantity over one point.
struct Series {
  Moments measured, reference, error;
  void Add(double m, double r) {
    measured.Add(m);
    reference.Add(r);
    error.Add(m - r);
  }
};

// The rest record's curve of one quantity and the time the limit counts wander over; `terms` is
// null without a rest record, `rate` says whether the point gets a physical limit.
struct NoiseModel {
  const AllanTerms* terms = nullptr;
  bool rate = false;
  double since_calibration_s = 0.0;
};

AcceptancePoint Judge(AcceptancePoint p,
                      const Series& s,
                      double tolerance,
                      double marginal_band,
                      const NoiseModel& noise = {}) {
  p.samples = s.error.n;
  p.measured = s.measured.Mean();
  p.reference = s.reference.Mean();
  p.error = s.error.Mean();
  p.std_error = s.error.StdError();
  p.noise = p.std_error;
  if (noise.terms != nullptr) {
    p.noise = PointSigma(*noise.terms, p.std_error, p.duration_s);
    if (noise.rate) {
      p.physical_limit =
          PointLimit(*noise.terms, p.std_error, p.duration_s, noise.since_calibration_s);
    }
  }
  p.tolerance = tolerance;
  p.marginal_band = marginal_band;
  p.pass = std::abs(p.error) <= tolerance;
  p.beyond_noise = std::abs(std::abs(p.error) - tolerance) > 2.0 * p.noise;
  return p;
}

double CheckedChamberC(const Where& where, const Moments& chamber, const Specification& spec) {
  const double c = chamber.Mean();
  if (c < spec.temp_min_c - kRatingMarginC || c > spec.temp_max_c + kRatingMarginC) {
    Refuse(where,
           fmt::format("chamber temperature {:.2f} degC is outside the rating {}...{} degC "
                       "(margin {} degC): no tolerance is specified there",
                       c,
                       spec.temp_min_c,
                       spec.temp_max_c,
                       kRatingMarginC));
  }
  return c;
}

double ToleranceAt(const Where& where, const ToleranceTable& table, double input) {
  try {
    return table.At(input);
  } catch (const std::out_of_range& e) {
    Refuse(where, e.what());
  }
}

// What acceptance keeps of one ADS row: the columns it judges.
struct AdsOutputRow {
  double t_s = 0.0;
  double chamber_c = 0.0;
  double ps_ref_pa = 0.0;
  double qc_ref_pa = 0.0;
  std::optional<double> alt_ft;
  std::optional<double> cas_kt;
  int step = 0;
  uint8_t tag = 0;
  uint8_t mode = 0;

  static AdsOutputRow Of(const hil::AdsRecordRow& row) {
    return {row.t_s,
            row.chamber_c,
            row.ps_ref_pa,
            row.qc_ref_pa,
            row.alt_ft,
            row.cas_kt,
            row.step,
            row.tag,
            row.mode};
  }
};

template <typename Row>
using RowsByUnit = std::map<std::string, std::vector<Row>>;

struct RunContext {
  std::string run;
  double packet_period_s = 0.0;
  double since_calibration_s = 0.0;
  hil::Recording recording;  ///< meta.json and the rejected intervals; no rows
  RowsByUnit<ImuOutputRow> imu;
  RowsByUnit<AdsOutputRow> ads;
  Sequence sequence;
  std::vector<uint8_t> tags;
};

// One streamed pass over the run: each row kept in its compact form, per unit in file order.
void ReadRows(const std::filesystem::path& run_dir, RunContext* ctx) {
  hil::RowSinks sinks;
  sinks.imu = [ctx](hil::ImuRecordRow&& row, int) {
    ctx->imu[row.unit].push_back(ImuOutputRow::Of(row));
  };
  sinks.ads = [ctx](hil::AdsRecordRow&& row, int) {
    ctx->ads[row.unit].push_back(AdsOutputRow::Of(row));
  };
  ctx->recording = hil::StreamRecording(run_dir, sinks);
}

template <typename Row>
bool Rejected(const RunContext& ctx, const Row& row) {
  for (const hil::RejectedInterval& r : ctx.recording.meta.rejected_intervals) {
    if (r.step == row.step && row.t_s >= r.t_start_s && row.t_s <= r.t_end_s) return true;
  }
  return false;
}

// The calibration rows of each (unit, step): the step's TAG, outside the rejected intervals.
template <typename Row>
std::map<std::pair<std::string, int>, std::vector<const Row*>> SelectRows(
    const RunContext& ctx, const RowsByUnit<Row>& by_unit) {
  std::map<std::pair<std::string, int>, std::vector<const Row*>> out;
  for (const auto& [unit, rows] : by_unit) {
    for (const Row& row : rows) {
      if (row.step < 0 || row.step >= static_cast<int>(ctx.tags.size()) || row.tag == 0 ||
          row.tag != ctx.tags[static_cast<size_t>(row.step)] || Rejected(ctx, row)) {
        continue;
      }
      out[{unit, row.step}].push_back(&row);
    }
  }
  return out;
}

template <typename Row>
const std::vector<const Row*>& RowsOf(
    const std::map<std::pair<std::string, int>, std::vector<const Row*>>& selected,
    const Where& where) {
  const auto it = selected.find({where.serial, where.step});
  if (it == selected.end() || it->second.empty()) {
    Refuse(where, "no rows with the step's tag (the unit is missing from the step)");
  }
  return it->second;
}

// The one mode of a step's rows; raw and thermal modes are refused.
template <typename Row>
int StepMode(const Where& where, const std::vector<const Row*>& rows, bool imu) {
  const int mode = rows.front()->mode;
  for (const Row* row : rows) {
    if (row->mode != mode) {
      Refuse(where, fmt::format("rows mix modes {} and {}", mode, static_cast<int>(row->mode)));
    }
  }
  if (mode == 0) {
    Refuse(where,
           "rows are in raw mode (0): no compensated output to judge; an acceptance run "
           "needs the unit in its calibrated mode");
  }
  if (imu && mode == 1) {
    Refuse(where,
           "rows are in thermal mode (1), which has no engineering units; an acceptance "
           "run needs mode 2 or 3");
  }
  return mode;
}

// --- IMU ---

std::array<double, 3> UpAxis(const Where& where, int orientation) {
  if (!IsOrientationCode(orientation)) {
    Refuse(where,
           fmt::format("orientation {} is not a fixture orientation code (11...32)", orientation));
  }
  std::array<double, 3> up{};
  up[static_cast<size_t>(orientation / 10 - 1)] = orientation % 10 == 1 ? 1.0 : -1.0;
  return up;
}

// One acquisition of an IMU step: its rows, orientation and commanded rate.
struct ImuGroup {
  int orientation = 0;
  std::optional<double> rate_cmd_dps;
  bool judge_accel = false;
  bool judge_rate = false;
  std::vector<const ImuOutputRow*> rows;
};

std::vector<ImuGroup> GroupImuStep(const Where& where,
                                   const StepBody& body,
                                   const std::vector<const ImuOutputRow*>& rows) {
  std::vector<ImuGroup> groups;
  std::vector<double> commands;
  if (const auto* g = std::get_if<GyroStep>(&body)) commands = GyroRates_dps(*g);
  if (const auto* c = std::get_if<CrossAxisStep>(&body)) commands = {0.0, c->rate_dps};
  const bool thermal = std::holds_alternative<ThermalProfileStep>(body);
  std::map<std::pair<int, double>, size_t> index;  // (orientation, command or bin) -> group
  for (const ImuOutputRow* row : rows) {
    double key = 0.0;
    std::optional<double> rate_cmd;
    if (!commands.empty()) {
      const auto nearest =
          std::min_element(commands.begin(), commands.end(), [&](double a, double b) {
            return std::abs(a - row->table_rate_dps) < std::abs(b - row->table_rate_dps);
          });
      if (std::abs(*nearest - row->table_rate_dps) > kRateMatch_dps) {
        Refuse(where,
               fmt::format("t_s {}: reported table rate {} deg/s matches no commanded rate",
                           row->t_s,
                           row->table_rate_dps));
      }
      key = *nearest;
      rate_cmd = *nearest;
    } else if (thermal) {
      key = std::floor(row->chamber_c / kThermalBinWidthC);
    }
    const auto [it, added] = index.try_emplace({row->orientation, key}, groups.size());
    if (added) {
      ImuGroup group;
      group.orientation = row->orientation;
      group.rate_cmd_dps = rate_cmd;
      group.judge_accel = !rate_cmd || *rate_cmd == 0.0;
      group.judge_rate = rate_cmd.has_value() || thermal;
      if (std::holds_alternative<GyroStep>(body)) group.judge_accel = false;
      if (std::holds_alternative<CrossAxisStep>(body)) group.judge_rate = *rate_cmd != 0.0;
      groups.push_back(group);
    }
    groups[it->second].rows.push_back(row);
  }
  // Every command must have been acquired in every orientation the step visits.
  if (!commands.empty()) {
    std::vector<int> orientations;
    if (const auto* g = std::get_if<GyroStep>(&body)) orientations = {g->orientation};
    if (std::holds_alternative<CrossAxisStep>(body)) {
      orientations.assign(std::begin(kCrossAxisOrientations), std::end(kCrossAxisOrientations));
    }
    for (int o : orientations) {
      for (double r : commands) {
        if (!index.count({o, r})) {
          Refuse(where,
                 fmt::format("no rows at the commanded rate {} deg/s in orientation {}", r, o));
        }
      }
    }
  }
  return groups;
}

void JudgeImuGroup(const Where& where,
                   const ImuGroup& group,
                   const Specification& spec,
                   double g_local_g,
                   const RunContext& ctx,
                   UnitAcceptance* unit) {
  if (group.rows.size() < 2) Refuse(where, "fewer than 2 rows in an acquisition");
  if (group.orientation == 0) Refuse(where, "rows carry no orientation (0: not mounted)");
  const std::array<double, 3> up = UpAxis(where, group.orientation);
  std::array<Series, 3> accel_mg, rate_dps;
  Moments chamber;
  for (const ImuOutputRow* row : group.rows) {
    const ImuBodyOutput& m = row->body;
    for (size_t i = 0; i < 3; ++i) {
      accel_mg[i].Add(m.f_B_g[i] * kMgPerG, up[i] * g_local_g * kMgPerG);
      rate_dps[i].Add(m.w_B_dps[i], up[i] * row->table_rate_dps);
    }
    chamber.Add(row->chamber_c);
  }
  AcceptancePoint base;
  base.step = where.step;
  base.kind = where.kind;
  base.orientation = group.orientation;
  base.rate_dps = group.rate_cmd_dps;
  base.chamber_c = CheckedChamberC(where, chamber, spec);
  base.duration_s = static_cast<double>(group.rows.size()) * ctx.packet_period_s;
  if (group.rate_cmd_dps && std::abs(*group.rate_cmd_dps) > spec.rated_rate_dps) {
    Refuse(where,
           fmt::format("commanded rate {} deg/s is outside the rated +-{} deg/s of {}",
                       *group.rate_cmd_dps,
                       spec.rated_rate_dps,
                       spec.name));
  }
  for (size_t i = 0; i < 3; ++i) {
    if (group.judge_accel) {
      AcceptancePoint p = base;
      p.quantity = std::string("accel_") + kAxisNames[i];
      p.unit = "mg";
      const NoiseModel noise{unit->rest ? &unit->rest->accel_mg[i] : nullptr, false, 0.0};
      unit->points.push_back(
          Judge(p, accel_mg[i], spec.accel_mg, spec.marginal_band.acceleration, noise));
    }
  }
  for (size_t i = 0; i < 3; ++i) {
    if (group.judge_rate) {
      AcceptancePoint p = base;
      p.quantity = std::string("rate_") + kAxisNames[i];
      p.unit = "deg/s";
      const NoiseModel noise{
          unit->rest ? &unit->rest->rate_dps[i] : nullptr, true, ctx.since_calibration_s};
      unit->points.push_back(
          Judge(p, rate_dps[i], spec.body_rate_dps, spec.marginal_band.body_rate, noise));
    }
  }
}

// The thermal acceptance of one thermal_profile step: per body axis the standard deviation, over
// the step, of the error averaged over consecutive kThermalStabilityMean_s blocks of packets (a
// last, shorter block is left out). Its standard error is that of a normal sample's deviation,
// s / sqrt(2 (n - 1)).
void JudgeThermalStability(const Where& where,
                           const std::vector<const ImuOutputRow*>& rows,
                           const ThermalStability& limits,
                           double g_local_g,
                           const RunContext& ctx,
                           UnitAcceptance* unit) {
  const int orientation = rows.front()->orientation;
  if (orientation == 0) Refuse(where, "rows carry no orientation (0: not mounted)");
  const std::array<double, 3> up = UpAxis(where, orientation);
  const auto block =
      static_cast<size_t>(std::max(1L, std::lround(kThermalStabilityMean_s / ctx.packet_period_s)));
  std::array<Moments, 3> accel_mg, rate_dps;
  std::array<double, 3> accel_sum{}, rate_sum{};
  size_t in_block = 0;
  Moments chamber;
  double chamber_min_c = rows.front()->chamber_c, chamber_max_c = chamber_min_c;
  for (const ImuOutputRow* row : rows) {
    if (row->orientation != orientation) {
      Refuse(where,
             fmt::format("t_s {}: orientation {} where the profile began in {}",
                         row->t_s,
                         row->orientation,
                         orientation));
    }
    for (size_t i = 0; i < 3; ++i) {
      accel_sum[i] += (row->body.f_B_g[i] - up[i] * g_local_g) * kMgPerG;
      rate_sum[i] += row->body.w_B_dps[i] - up[i] * row->table_rate_dps;
    }
    chamber.Add(row->chamber_c);
    chamber_min_c = std::min(chamber_min_c, row->chamber_c);
    chamber_max_c = std::max(chamber_max_c, row->chamber_c);
    if (++in_block < block) continue;
    for (size_t i = 0; i < 3; ++i) {
      accel_mg[i].Add(accel_sum[i] / static_cast<double>(block));
      rate_dps[i].Add(rate_sum[i] / static_cast<double>(block));
    }
    accel_sum = {};
    rate_sum = {};
    in_block = 0;
  }
  if (accel_mg[0].n < 2) {
    Refuse(where,
           fmt::format("{} packets: fewer than two {:g} s means for the thermal acceptance's "
                       "standard deviation",
                       rows.size(),
                       kThermalStabilityMean_s));
  }
  AcceptancePoint base;
  base.step = where.step;
  base.kind = where.kind;
  base.orientation = orientation;
  base.chamber_c = chamber.Mean();
  base.chamber_min_c = chamber_min_c;
  base.chamber_max_c = chamber_max_c;
  base.samples = accel_mg[0].n * static_cast<int>(block);
  base.duration_s = static_cast<double>(base.samples) * ctx.packet_period_s;
  base.reference = 0.0;
  base.marginal_band = limits.marginal_band;
  for (const bool rate : {false, true}) {
    for (size_t i = 0; i < 3; ++i) {
      const Moments& m = rate ? rate_dps[i] : accel_mg[i];
      AcceptancePoint p = base;
      p.quantity = std::string(rate ? "thermal_rate_std_" : "thermal_accel_std_") + kAxisNames[i];
      p.unit = rate ? "deg/s" : "mg";
      p.measured = m.Std();
      p.error = p.measured;
      p.std_error = p.measured / std::sqrt(2.0 * (m.n - 1));
      p.noise = p.std_error;
      p.tolerance = rate ? limits.rate_std_dps : limits.accel_std_mg;
      p.pass = p.error <= p.tolerance;
      p.beyond_noise = std::abs(p.error - p.tolerance) > 2.0 * p.noise;
      unit->points.push_back(p);
    }
  }
}

void JudgeImuUnit(
    const RunContext& ctx,
    const Specification& spec,
    double g_local_mps2,
    const std::map<std::pair<std::string, int>, std::vector<const ImuOutputRow*>>& selected,
    UnitAcceptance* unit) {
  const auto own = ctx.imu.find(unit->serial);
  unit->rest = ReadRestStability(own == ctx.imu.end() ? std::vector<ImuOutputRow>{} : own->second,
                                 ctx.packet_period_s);
  for (size_t s = 0; s < ctx.sequence.steps.size(); ++s) {
    const StepBody& body = ctx.sequence.steps[s].body;
    const bool acquires = std::holds_alternative<AccelStep>(body) ||
                          std::holds_alternative<GyroStep>(body) ||
                          std::holds_alternative<CrossAxisStep>(body) ||
                          std::holds_alternative<ThermalProfileStep>(body);
    if (!acquires) continue;
    const Where where{ctx.run, unit->serial, static_cast<int>(s), StepKindName(body), ctx.tags[s]};
    const auto& rows = RowsOf(selected, where);
    const int mode = StepMode(where, rows, true);
    if (unit->mode != 0 && unit->mode != mode) {
      Refuse(where,
             fmt::format("rows in mode {} where earlier steps were in mode {}", mode, unit->mode));
    }
    unit->mode = mode;
    std::optional<int> commanded;
    if (const auto* a = std::get_if<AccelStep>(&body)) commanded = a->orientation;
    if (const auto* g = std::get_if<GyroStep>(&body)) commanded = g->orientation;
    for (const ImuOutputRow* row : rows) {
      if (commanded && row->orientation != *commanded) {
        Refuse(where,
               fmt::format("t_s {}: orientation {} where the step commands {}",
                           row->t_s,
                           row->orientation,
                           *commanded));
      }
    }
    for (const ImuGroup& group : GroupImuStep(where, body, rows)) {
      // A thermal bin the chamber only touched (a turning point, the profile's last value) holds
      // too few packets for a mean and its standard error; it is not judged.
      if (std::holds_alternative<ThermalProfileStep>(body) &&
          group.rows.size() < kMinThermalBinPackets) {
        continue;
      }
      JudgeImuGroup(where, group, spec, common::Mps2ToG(g_local_mps2), ctx, unit);
    }
    if (std::holds_alternative<ThermalProfileStep>(body) && spec.thermal_stability) {
      JudgeThermalStability(
          where, rows, *spec.thermal_stability, common::Mps2ToG(g_local_mps2), ctx, unit);
    }
  }
}

// --- ADS ---

void JudgeAdsUnit(
    const RunContext& ctx,
    const Specification& spec,
    const std::map<std::pair<std::string, int>, std::vector<const AdsOutputRow*>>& selected,
    UnitAcceptance* unit) {
  std::optional<double> alt_aim_ft;
  std::optional<double> cas_aim_kt;
  for (size_t s = 0; s < ctx.sequence.steps.size(); ++s) {
    const StepBody& body = ctx.sequence.steps[s].body;
    if (const auto* a = std::get_if<AltitudeStep>(&body)) alt_aim_ft = a->alt_ft;
    if (const auto* a = std::get_if<AirspeedStep>(&body)) cas_aim_kt = a->cas_kt;
    if (!std::holds_alternative<LogStep>(body)) continue;
    const Where where{ctx.run, unit->serial, static_cast<int>(s), StepKindName(body), ctx.tags[s]};
    const auto& rows = RowsOf(selected, where);
    if (rows.size() < 2) Refuse(where, "fewer than 2 rows in the acquisition");
    unit->mode = StepMode(where, rows, false);
    Series alt_ft, cas_kt;
    Moments chamber;
    const double duration_s = rows.back()->t_s - rows.front()->t_s + ctx.packet_period_s;
    for (const AdsOutputRow* row : rows) {
      double ref_alt_ft = 0.0;
      double ref_cas_kt = 0.0;
      try {
        ref_alt_ft = common::IsaPressureAltitudeFt(row->ps_ref_pa);
        ref_cas_kt = common::CalibratedAirspeedKt(std::max(0.0, row->qc_ref_pa));
      } catch (const std::exception& e) {
        Refuse(where,
               fmt::format("t_s {}: reference ps_ref_pa {} / qc_ref_pa {}: {}",
                           row->t_s,
                           row->ps_ref_pa,
                           row->qc_ref_pa,
                           e.what()));
      }
      alt_ft.Add(*row->alt_ft, ref_alt_ft);
      cas_kt.Add(*row->cas_kt, ref_cas_kt);
      chamber.Add(row->chamber_c);
    }
    AcceptancePoint base;
    base.step = where.step;
    base.kind = where.kind;
    base.chamber_c = CheckedChamberC(where, chamber, spec);
    base.duration_s = duration_s;
    base.alt_ft = alt_aim_ft.value_or(alt_ft.reference.Mean());
    base.cas_kt = cas_aim_kt.value_or(cas_kt.reference.Mean());
    AcceptancePoint alt = base;
    alt.quantity = "altitude";
    alt.unit = "ft";
    unit->points.push_back(Judge(alt,
                                 alt_ft,
                                 ToleranceAt(where, spec.altitude_ft, *base.alt_ft),
                                 spec.marginal_band.altitude));
    if (*base.cas_kt >= spec.airspeed_kt.input_min()) {
      AcceptancePoint cas = base;
      cas.quantity = "airspeed";
      cas.unit = "kt";
      unit->points.push_back(Judge(cas,
                                   cas_kt,
                                   ToleranceAt(where, spec.airspeed_kt, *base.cas_kt),
                                   spec.marginal_band.airspeed));
    }
  }
}

}  // namespace

const char* OutcomeText(Outcome outcome) {
  switch (outcome) {
    case Outcome::kPass:
      return "PASS";
    case Outcome::kMarginal:
      return "MARGINAL";
    case Outcome::kFail:
      return "FAIL";
  }
  return "?";
}

const char* PointVerdictText(PointVerdict verdict) {
  switch (verdict) {
    case PointVerdict::kWithinSpecification:
      return "within specification";
    case PointVerdict::kWithinPhysicalLimit:
      return "outside specification, within the physical limit";
    case PointVerdict::kOutsideBoth:
      return "outside specification and the physical limit";
    case PointVerdict::kOutsideSpecification:
      return "outside specification";
  }
  return "?";
}

std::string QuantityFamily(const std::string& quantity) {
  if (quantity.starts_with("accel_")) return "acceleration";
  if (quantity.starts_with("rate_")) return "body_rate";
  if (quantity.starts_with("thermal_accel_std_")) return "thermal_acceleration_std";
  if (quantity.starts_with("thermal_rate_std_")) return "thermal_body_rate_std";
  return quantity;
}

double AcceptancePoint::margin() const { return tolerance - std::abs(error); }

PointVerdict AcceptancePoint::verdict() const {
  if (pass) return PointVerdict::kWithinSpecification;
  if (!physical_limit) return PointVerdict::kOutsideSpecification;
  return std::abs(error) <= *physical_limit ? PointVerdict::kWithinPhysicalLimit
                                            : PointVerdict::kOutsideBoth;
}

Outcome AcceptancePoint::outcome() const {
  if (!pass) return Outcome::kFail;
  return std::abs(error) > (1.0 - marginal_band) * tolerance ? Outcome::kMarginal : Outcome::kPass;
}

std::string AcceptancePoint::Condition() const {
  std::string text;
  if (orientation != 0) text += fmt::format("orientation {}, ", orientation);
  if (rate_dps) text += fmt::format("{:g} deg/s, ", *rate_dps);
  if (alt_ft) text += fmt::format("{:g} ft, ", *alt_ft);
  if (cas_kt && *cas_kt > 0.0) text += fmt::format("{:g} kt, ", *cas_kt);
  if (chamber_min_c && chamber_max_c) {
    return text + fmt::format("{:.1f}...{:.1f} degC", *chamber_min_c, *chamber_max_c);
  }
  return text + fmt::format("{:.1f} degC", chamber_c);
}

bool UnitAcceptance::pass() const { return failed() == 0; }

int UnitAcceptance::failed() const {
  return static_cast<int>(std::count_if(
      points.begin(), points.end(), [](const AcceptancePoint& p) { return !p.pass; }));
}

int UnitAcceptance::marginal() const {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [](const AcceptancePoint& p) {
    return p.outcome() == Outcome::kMarginal;
  }));
}

Outcome UnitAcceptance::outcome() const {
  if (failed() > 0) return Outcome::kFail;
  return marginal() > 0 ? Outcome::kMarginal : Outcome::kPass;
}

int UnitAcceptance::Count(const std::string& family, PointVerdict verdict) const {
  return static_cast<int>(
      std::count_if(points.begin(), points.end(), [&](const AcceptancePoint& p) {
        return QuantityFamily(p.quantity) == family && p.verdict() == verdict;
      }));
}

std::vector<WorstMargin> UnitAcceptance::WorstMargins() const {
  std::vector<WorstMargin> out;
  for (const AcceptancePoint& p : points) {
    const std::string family = QuantityFamily(p.quantity);
    auto it = std::find_if(
        out.begin(), out.end(), [&](const WorstMargin& w) { return w.quantity == family; });
    const WorstMargin candidate{
        family, p.unit, p.margin(), p.step, p.quantity + " at " + p.Condition()};
    if (it == out.end()) {
      out.push_back(candidate);
    } else if (p.margin() < it->margin) {
      *it = candidate;
    }
  }
  return out;
}

bool AcceptanceRun::pass() const {
  return std::all_of(units.begin(), units.end(), [](const UnitAcceptance& u) { return u.pass(); });
}

AcceptanceRun JudgeAcceptance(const std::filesystem::path& run_dir,
                              const Specification& spec,
                              const AcceptanceOptions& options) {
  RunContext ctx;
  ctx.run = run_dir.string();
  const auto fail = [&](const std::string& message) {
    throw AcceptanceInputError(ctx.run + ": " + message);
  };
  if (!(options.since_calibration_h >= 0.0 &&
        options.since_calibration_h <= kMaxSinceCalibration_h)) {
    fail(fmt::format("the time since calibration {} h is outside 0...{} h",
                     options.since_calibration_h,
                     kMaxSinceCalibration_h));
  }
  ctx.since_calibration_s = options.since_calibration_h * 3600.0;
  ReadRows(run_dir, &ctx);
  const hil::RecordingMeta& meta = ctx.recording.meta;
  ctx.packet_period_s = 1.0 / kDefaultSampleRate_hz;
  if (meta.sample_rate_hz) {
    if (!(*meta.sample_rate_hz > 0.0)) fail("meta.json: $.sample_rate_hz is not a positive number");
    ctx.packet_period_s = 1.0 / *meta.sample_rate_hz;
  }
  if (!meta.sequence) fail("meta.json: $.sequence missing");
  ctx.sequence = SequenceFromJson(*meta.sequence, ctx.run + "/meta.json $.sequence");
  ctx.tags = EffectiveTags(ctx.sequence);

  AcceptanceRun run;
  run.run_dir = ctx.run;
  run.run_id = meta.run_id.value_or(run_dir.filename().string());
  run.recording_sha256 = RecordingSha256(run_dir);
  run.sequence_name = ctx.sequence.name;
  run.since_calibration_h = options.since_calibration_h;
  if (!meta.has_units) fail("meta.json: $.units missing");
  for (size_t i = 0; i < meta.units.size(); ++i) {
    const hil::RecordingUnit& u = meta.units[i];
    const std::string path = fmt::format("meta.json: $.units[{}]", i);
    if (u.serial.empty()) fail(path + ".serial missing");
    if (!u.kind) fail(path + ".kind missing");
    if (*u.kind == ctx.sequence.unit_kind) {
      run.units.push_back({u.serial, common::UnitKindName(*u.kind), 0, {}, std::nullopt});
    }
  }
  if (run.units.empty()) {
    fail(fmt::format("meta.json: $.units lists no {} unit (the sequence's unit kind)",
                     UnitKindName(ctx.sequence.unit_kind)));
  }
  const bool has_imu = std::any_of(
      run.units.begin(), run.units.end(), [](const UnitAcceptance& u) { return u.kind == "imu"; });
  if (has_imu) {
    if (!meta.local_gravity_mps2) {
      fail(
          "meta.json: $.local_gravity_mps2 missing (the station's local gravity is the "
          "accelerometers' reference)");
    }
    run.local_gravity_mps2 = *meta.local_gravity_mps2;
    if (!(run.local_gravity_mps2 > 9.7 && run.local_gravity_mps2 < 9.9)) {
      fail(
          fmt::format("meta.json: $.local_gravity_mps2 {} is not Earth's", run.local_gravity_mps2));
    }
  }
  const auto imu_rows = SelectRows(ctx, ctx.imu);
  const auto ads_rows = SelectRows(ctx, ctx.ads);
  for (UnitAcceptance& unit : run.units) {
    if (unit.kind == "imu") {
      JudgeImuUnit(ctx, spec, run.local_gravity_mps2, imu_rows, &unit);
    } else {
      JudgeAdsUnit(ctx, spec, ads_rows, &unit);
    }
    if (unit.points.empty()) {
      fail("unit " + unit.serial + ": the sequence has no step that acquires " + unit.kind +
           " data");
    }
  }
  return run;
}

}  // namespace adahrs::calib
