#include "calib/imu_calibration/imu_run_data.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "calib/constants/recording_checksum.h"
#include "calib/sequence/sequence_json.h"
#include "hil/recording/recording_reader.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

constexpr int32_t kGyroCountMax = 16 * ((1 << 19) - 1);  // 16 summed 19-bit conversions
constexpr uint16_t kTempCountMax = 16 * 4095;            // 16 summed 12-bit conversions
constexpr double kRateGroupWidth_dps = 1.0;
constexpr double kTrendWindow_s = 30.0;
constexpr double kTrendThreshold_c_per_s = 0.05 / 60.0;
constexpr const char* kAccelColumns[12] = {"az1_t1",
                                           "az1_t2",
                                           "ax1_t1",
                                           "ax1_t2",
                                           "ay1_t1",
                                           "ay1_t2",
                                           "az2_t1",
                                           "az2_t2",
                                           "ax2_t1",
                                           "ax2_t2",
                                           "ay2_t1",
                                           "ay2_t2"};
constexpr const char* kGyroColumns[3] = {"gx", "gy", "gz"};
constexpr const char* kTempColumns[3] = {"tx", "ty", "tz"};

// The reason a row cannot be calibration data, with its column, or empty.
// Every mode's packet carries the raw counts (docs/unit-protocol.md), so a row of a compensated
// mode (the staged process records mode 1 and 2) is calibration data as a raw one is.
std::string RowDefect(const hil::ImuRecordRow& row) {
  for (int ch = 0; ch < 6; ++ch) {
    const uint16_t t1 = row.accel_ticks[2 * ch];
    const uint16_t t2 = row.accel_ticks[2 * ch + 1];
    if (t2 == 0 || t1 >= t2) {
      return std::string("column ") + kAccelColumns[2 * ch] + ": t1 " + std::to_string(t1) +
             " >= t2 " + std::to_string(t2) + " (duty undefined)";
    }
  }
  for (int g = 0; g < 3; ++g) {
    if (row.gyro_cnt[g] <= 0 || row.gyro_cnt[g] >= kGyroCountMax) {
      return std::string("column ") + kGyroColumns[g] + ": " + std::to_string(row.gyro_cnt[g]) +
             " at the converter limit (saturated)";
    }
    if (row.temp_cnt[g] == 0 || row.temp_cnt[g] >= kTempCountMax) {
      return std::string("column ") + kTempColumns[g] + ": " + std::to_string(row.temp_cnt[g]) +
             " at the converter limit (saturated)";
    }
  }
  return {};
}

ImuSample ToSample(const hil::ImuRecordRow& row) {
  ImuSample s;
  s.raw = RawFrameOf(row);
  s.t_s = row.t_s;
  s.chamber_c = row.chamber_c;
  s.table_rate_dps = row.table_rate_dps;
  s.seq = static_cast<uint8_t>(row.seq & 0xFF);
  return s;
}

// Groups samples by reported table rate (and orientation): one acquisition per group.
void GroupByRate(const std::string& run,
                 int step,
                 const std::string& kind,
                 const std::vector<int>& orientations,
                 const std::vector<ImuSample>& samples,
                 std::vector<ImuAcquisition>* out) {
  std::vector<ImuAcquisition> groups;
  for (size_t i = 0; i < samples.size(); ++i) {
    const ImuSample& s = samples[i];
    ImuAcquisition* group = nullptr;
    for (ImuAcquisition& g : groups) {
      if (g.orientation == orientations[i] &&
          std::abs(g.samples.front().table_rate_dps - s.table_rate_dps) < kRateGroupWidth_dps) {
        group = &g;
      }
    }
    if (!group) {
      groups.push_back({run, step, kind, orientations[i], 0.0, {}});
      group = &groups.back();
    }
    group->samples.push_back(s);
  }
  for (ImuAcquisition& g : groups) {
    double sum = 0.0;
    for (const ImuSample& s : g.samples) sum += s.table_rate_dps;
    g.rate_dps = sum / static_cast<double>(g.samples.size());
    out->push_back(std::move(g));
  }
}

// Rows of several runs follow each other (each run's clock starts at zero): the trend window
// never reaches into another run.
std::vector<ThermalSegment> Segments(const std::vector<ImuSample>& rows) {
  std::vector<ThermalSegment> out(rows.size(), ThermalSegment::kSoak);
  size_t lo = 0, hi = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[lo].run != rows[i].run) lo = hi = i;
    while (rows[lo].t_s < rows[i].t_s - kTrendWindow_s) ++lo;
    while (hi + 1 < rows.size() && rows[hi + 1].run == rows[i].run &&
           rows[hi + 1].t_s <= rows[i].t_s + kTrendWindow_s) {
      ++hi;
    }
    const double dt = rows[hi].t_s - rows[lo].t_s;
    if (dt <= 0.0) continue;
    const double slope = (rows[hi].chamber_c - rows[lo].chamber_c) / dt;
    if (slope > kTrendThreshold_c_per_s) out[i] = ThermalSegment::kUpRamp;
    if (slope < -kTrendThreshold_c_per_s) out[i] = ThermalSegment::kDownRamp;
  }
  return out;
}

void LoadRun(const std::filesystem::path& dir, ImuRunData* data) {
  const hil::Recording rec = hil::ReadRecordingMeta(dir);  // the rows are streamed below
  const std::string run = dir.string();
  auto fail = [&](const std::string& message) { throw ImuInputError(run + ": " + message); };
  const hil::RecordingMeta& meta = rec.meta;
  if (!meta.local_gravity_mps2) {
    fail("meta.json: $.local_gravity_mps2 missing (the station's local gravity is needed)");
  }
  const double g = *meta.local_gravity_mps2;
  if (!meta.sequence) fail("meta.json: $.sequence missing");
  const Sequence sequence = SequenceFromJson(*meta.sequence, run + "/meta.json $.sequence");
  std::vector<std::string> serials;
  for (const hil::RecordingUnit& u : meta.units) {
    if (u.kind == hil::UnitKind::kImu && !u.serial.empty()) serials.push_back(u.serial);
  }
  ImuRunCollector collector(
      run, RecordingSha256(dir), sequence, g, serials, rec.meta.rejected_intervals, data);
  // Rows streamed from imu.csv: a recording of ten million rows is never held twice.
  const hil::Recording read = hil::StreamRecording(
      dir, {[&](hil::ImuRecordRow&& row, int line) { collector.Take(row, line); }, {}});
  data->notes.insert(data->notes.end(), read.notes.begin(), read.notes.end());
  collector.Finish();
}

}  // namespace

ImuRunCollector::ImuRunCollector(std::string run,
                                 std::string sha256,
                                 const Sequence& sequence,
                                 double local_gravity_mps2,
                                 std::vector<std::string> serials,
                                 std::vector<hil::RejectedInterval> rejected,
                                 ImuRunData* data)
    : run_(std::move(run)),
      sequence_(sequence),
      tags_(EffectiveTags(sequence)),
      serials_(std::move(serials)),
      rejected_(std::move(rejected)),
      data_(data) {
  const double g = local_gravity_mps2;
  if (!(g > 9.7 && g < 9.9))
    Fail("meta.json: $.local_gravity_mps2 " + std::to_string(g) + " is not Earth's");
  if (data_->local_gravity_mps2 != 0.0 && std::abs(data_->local_gravity_mps2 - g) > 1e-9) {
    Fail("local gravity " + std::to_string(g) + " m/s^2 differs from the first run's " +
         std::to_string(data_->local_gravity_mps2) + " (runs from different stations)");
  }
  if (serials_.empty()) Fail("meta.json: $.units lists no IMU");
  data_->local_gravity_mps2 = g;
  run_index_ = static_cast<int>(data_->recordings.size());
  data_->sequence_names.push_back(sequence.name);
  data_->recordings.push_back({run_, std::move(sha256)});
}

void ImuRunCollector::Fail(const std::string& message) const {
  throw ImuInputError(run_ + ": " + message);
}

void ImuRunCollector::Take(const hil::ImuRecordRow& row, int line) {
  if (row.step < 0 || row.step >= static_cast<int>(tags_.size()) || row.tag == 0 ||
      row.tag != tags_[static_cast<size_t>(row.step)]) {
    return;
  }
  if (!cached_data_ || row.step != cached_step_ || row.unit != cached_unit_) {
    if (std::find(serials_.begin(), serials_.end(), row.unit) == serials_.end()) return;
    cached_data_ = &data_->units[row.unit];
    cached_data_->serial = row.unit;
    cached_rows_ = &selected_[{row.unit, row.step}];
    cached_unit_ = row.unit;
    cached_step_ = row.step;
  }
  ImuUnitData& unit = *cached_data_;
  bool inside = false;
  for (const hil::RejectedInterval& r : rejected_) {
    inside |= r.step == row.step && row.t_s >= r.t_start_s && row.t_s <= r.t_end_s;
  }
  if (inside) {
    ++unit.rejected_interval_rows;
    return;
  }
  const std::string defect = RowDefect(row);
  if (!defect.empty()) {
    unit.exclusions.push_back(run_ + "/imu.csv line " + std::to_string(line) + " " + defect);
    return;
  }
  ImuSample sample = ToSample(row);
  sample.run = run_index_;
  cached_rows_->orientation.push_back(row.orientation);
  cached_rows_->samples.push_back(sample);
}

// The thermal rows are most of a run's, over several steps: each unit's are copied once into
// room made for all of them, not into a vector that grows (and is copied) step by step.
void ImuRunCollector::ReserveThermalRows() {
  std::map<std::string, size_t> rows_of;
  for (const auto& [key, rows] : selected_) {
    const auto step = static_cast<size_t>(key.second);
    if (std::holds_alternative<ThermalProfileStep>(sequence_.steps[step].body)) {
      rows_of[key.first] += rows.samples.size();
    }
  }
  for (const auto& [serial, rows] : rows_of) {
    std::vector<ImuSample>& thermal = data_->units[serial].thermal;
    thermal.reserve(thermal.size() + rows);
  }
}

void ImuRunCollector::Finish() {
  cached_data_ = nullptr;  // the rows' entries are moved out below
  cached_rows_ = nullptr;
  ReserveThermalRows();
  int current_orientation = 0;
  for (size_t step = 0; step < sequence_.steps.size(); ++step) {
    const StepBody& body = sequence_.steps[step].body;
    if (const auto* a = std::get_if<AccelStep>(&body)) current_orientation = a->orientation;
    if (const auto* gs = std::get_if<GyroStep>(&body)) current_orientation = gs->orientation;
    const bool acquires = std::holds_alternative<AccelStep>(body) ||
                          std::holds_alternative<GyroStep>(body) ||
                          std::holds_alternative<CrossAxisStep>(body) ||
                          std::holds_alternative<ThermalProfileStep>(body);
    if (!acquires) continue;
    const std::string where = "step " + std::to_string(step) + " (" + StepKindName(body) +
                              ", tag " + std::to_string(tags_[step]) + ")";
    for (const std::string& serial : serials_) {
      auto it = selected_.find({serial, static_cast<int>(step)});
      if (it == selected_.end() || it->second.samples.size() < 2) {
        Fail("unit " + serial + " is missing from " + where +
             ": fewer than 2 usable rows with the step's tag");
      }
      ImuUnitData& unit = data_->units[serial];
      unit.serial = serial;
      SelectedRows rows = std::move(it->second);  // freed after use
      selected_.erase(it);
      if (const auto* a = std::get_if<AccelStep>(&body)) {
        for (const int orientation : rows.orientation) {
          if (orientation != a->orientation) {
            Fail("unit " + serial + " " + where + ": a row carries orientation " +
                 std::to_string(orientation) + ", the step commands " +
                 std::to_string(a->orientation));
          }
        }
        unit.accel.push_back(
            {run_, static_cast<int>(step), "accel", a->orientation, 0.0, std::move(rows.samples)});
      } else if (std::holds_alternative<GyroStep>(body)) {
        GroupByRate(
            run_, static_cast<int>(step), "gyro", rows.orientation, rows.samples, &unit.gyro);
      } else if (std::holds_alternative<CrossAxisStep>(body)) {
        GroupByRate(run_,
                    static_cast<int>(step),
                    "cross_axis",
                    rows.orientation,
                    rows.samples,
                    &unit.cross_axis);
      } else {
        unit.thermal.insert(unit.thermal.end(), rows.samples.begin(), rows.samples.end());
        unit.thermal_orientation =
            rows.orientation.front() != 0 ? rows.orientation.front() : current_orientation;
      }
    }
  }
  LabelThermalSegments(data_);
}

void LabelThermalSegments(ImuRunData* data) {
  for (auto& [serial, unit] : data->units) unit.thermal_segment = Segments(unit.thermal);
}

std::array<double, 3> UpAxisOf(int orientation) {
  std::array<double, 3> up{};
  const int axis = orientation / 10 - 1;
  if (axis < 0 || axis > 2 || (orientation % 10 != 1 && orientation % 10 != 2)) {
    throw ImuInputError("orientation code " + std::to_string(orientation) + " is not 11...32");
  }
  up[static_cast<size_t>(axis)] = orientation % 10 == 1 ? 1.0 : -1.0;
  return up;
}

ImuRunData LoadImuRuns(const std::vector<std::filesystem::path>& run_dirs) {
  if (run_dirs.empty()) throw ImuInputError("no run directory given");
  ImuRunData data;
  for (const auto& dir : run_dirs) LoadRun(dir, &data);
  return data;
}

firmware_model::ImuRawFrame RawFrameOf(const hil::ImuRecordRow& row) {
  firmware_model::ImuRawFrame raw{};
  for (int ch = 0; ch < 6; ++ch) {
    raw.t1_cnt[ch] = row.accel_ticks[2 * ch];
    raw.t2_cnt[ch] = row.accel_ticks[2 * ch + 1];
  }
  for (int g = 0; g < 3; ++g) {
    raw.gyro_cnt[g] = row.gyro_cnt[g];
    raw.temp_cnt[g] = row.temp_cnt[g];
  }
  return raw;
}

}  // namespace adahrs::calib
