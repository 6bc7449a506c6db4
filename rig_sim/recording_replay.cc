#include "rig_sim/recording_replay.h"

#include <cmath>
#include <deque>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <variant>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "common/random.h"
#include "common/units.h"
#include "hil/recording/frame_count.h"
#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"
#include "rig_sim/fixture_orientation.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::rig_sim {
namespace {

namespace fs = std::filesystem;

// Rows held while the instruments have not reported yet: beyond this many, the zeros are taken as
// the instruments' values.
constexpr size_t kMaxHeldRows = 1000000;
// A unit's rows may arrive in bursts; a row this far before the unit's previous one is time going
// backwards.
constexpr double kBackwardsTolerance_s = 1.0;
// A gap longer than this between a unit's rows is not a soak but a broken time column; a first
// row later than this on the time base is not counted from power-on.
constexpr double kMaxGap_s = 30.0 * 86400.0;
// The noise stream under a unit's seed, as the rig and static_thermal_run.cc derive it.
constexpr uint64_t kNoiseStream = 1;

struct UnitFile {
  fs::path path;
  nlohmann::json file;
  std::string kind;
  std::string serial;
  std::optional<uint64_t> seed;  ///< the rig's seed of the unit, when the file is a truth file
};

UnitFile ReadUnitFile(const fs::path& path) {
  UnitFile u{path, common::ParamReader::LoadFile(path.string()), "", "", std::nullopt};
  const common::ParamReader top(u.file, path.string());
  u.kind = top.String("kind");
  if (top.Has("seed")) {
    const nlohmann::json& seed = u.file["seed"];
    if (!seed.is_number_unsigned()) top.Fail("$.seed", "not an unsigned 64-bit integer");
    u.seed = seed.get<uint64_t>();
  }
  const common::ParamReader params = top.Child("params");
  if (u.kind == "imu") {
    u.serial = sensor_sim::ImuUnitParams::FromJson(params).serial;
  } else if (u.kind == "ads") {
    u.serial = sensor_sim::AdsUnitParams::FromJson(params).serial;
  } else {
    top.Fail("$.kind", fmt::format("'{}' is neither imu nor ads", u.kind));
  }
  return u;
}

// A stable 64-bit hash of the serial (FNV-1a), so a unit's noise does not depend on the others.
uint64_t SerialStream(const std::string& serial) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : serial) h = (h ^ c) * 1099511628211ULL;
  return h;
}

// Frames a unit ran between its rows: the difference of the rows' frame indices where the
// recording has them (version 3: the recorder's exact count), else hil::FramesBetween from the
// packet counter and the arrival times. The first row counts from power-on at t = 0.
class FrameClock {
 public:
  FrameClock(double period_s, std::string where) : period_s_(period_s), where_(std::move(where)) {}

  int64_t FramesFor(double t_s, uint32_t seq, int64_t frame, int line) {
    int64_t n = 1;
    if (!started_) {
      started_ = true;
      if (t_s > 0.0 && t_s <= kMaxGap_s) {
        n = std::max<int64_t>(1, frame >= 0 ? frame : std::llround(t_s / period_s_));
      }
    } else {
      const double dt_s = t_s - last_t_s_;
      if (dt_s < -kBackwardsTolerance_s || dt_s > kMaxGap_s) {
        throw std::runtime_error(fmt::format(
            "{} line {}: t_s {} after the unit's row at {} s", where_, line, t_s, last_t_s_));
      }
      if (frame >= 0 && last_frame_ >= 0) {
        if (frame < last_frame_) {
          throw std::runtime_error(
              fmt::format("{} line {}: frame {} after the unit's row at frame {}",
                          where_,
                          line,
                          frame,
                          last_frame_));
        }
        n = frame - last_frame_;  // 0: the same packet logged twice
      } else {
        n = hil::FramesBetween(last_seq_, seq, dt_s, period_s_);  // 0: the same packet twice
      }
    }
    last_t_s_ = t_s;
    last_seq_ = seq;
    last_frame_ = frame;
    return n;
  }

 private:
  double period_s_;
  std::string where_;
  bool started_ = false;
  double last_t_s_ = 0.0;
  uint32_t last_seq_ = 0;
  int64_t last_frame_ = -1;
};

struct ImuReplayer {
  sensor_sim::ImuUnit unit;
  FrameClock clock;
  Eigen::Vector3d up_B = Eigen::Vector3d::UnitZ();
  sensor_sim::ImuRawFrame last;
};

struct AdsReplayer {
  sensor_sim::AdsUnit unit;
  FrameClock clock;
  sensor_sim::AdsRawFrame last;
};

// The first reported instrument values of one file, and the rows held until they are known.
template <typename Row>
class LeadingZeros {
 public:
  explicit LeadingZeros(std::function<bool(const Row&)> reported)
      : reported_(std::move(reported)) {}

  // Hands `row` (and the rows held before it) to `emit` once the instruments have reported. A held
  // row goes with the first reporting row, whose instrument values it takes; the others with null.
  template <typename Emit>
  void Add(Row&& row, int line, const Emit& emit) {
    if (!first_ && reported_(row)) first_ = row;
    if (!first_ && held_.size() < kMaxHeldRows) {
      held_.emplace_back(std::move(row), line);
      return;
    }
    Release(emit);
    emit(std::move(row), line, nullptr);
  }

  // Emits the held rows (at the end of the file: with the zeros when nothing was ever reported).
  template <typename Emit>
  void Release(const Emit& emit) {
    while (!held_.empty()) {
      emit(std::move(held_.front().first), held_.front().second, first_ ? &*first_ : nullptr);
      held_.pop_front();
    }
  }

 private:
  std::function<bool(const Row&)> reported_;
  std::optional<Row> first_;
  std::deque<std::pair<Row, int>> held_;
};

double LocalGravity(const hil::RecordingMeta& meta, const fs::path& run_dir) {
  if (meta.local_gravity_mps2) return *meta.local_gravity_mps2;
  // The station file as the executor read it: its schema is hil::Station's.
  if (meta.station && meta.station->is_object() && meta.station->contains("local_gravity_mps2") &&
      meta.station->at("local_gravity_mps2").is_number()) {
    return meta.station->at("local_gravity_mps2").get<double>();
  }
  throw std::runtime_error((run_dir / "meta.json").string() +
                           ": no local_gravity_mps2 (top level or in station): an IMU replay needs "
                           "the station's gravity");
}

void WriteJsonFile(const fs::path& path, const nlohmann::json& j) {
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

// The unit files by serial; two files of one serial are refused.
std::map<std::string, UnitFile> ReadUnitFiles(const std::vector<fs::path>& unit_files) {
  std::map<std::string, UnitFile> files;
  for (const fs::path& p : unit_files) {
    UnitFile u = ReadUnitFile(p);
    if (files.count(u.serial) != 0) {
      throw std::runtime_error(fmt::format("{}: a second unit file for {} (the first: {})",
                                           p.string(),
                                           u.serial,
                                           files.at(u.serial).path.string()));
    }
    files.emplace(u.serial, std::move(u));
  }
  return files;
}

// The recording's units that have a unit file (meta.json "units" of the replay), noted in
// `summary` as replayed or skipped. A unit file of another kind than the recorded unit, or of a
// serial the recording does not hold, is refused.
std::vector<hil::RecordingUnit> ReplayedUnits(const hil::RecordingMeta& meta,
                                              const std::map<std::string, UnitFile>& files,
                                              const fs::path& run_dir,
                                              ReplaySummary& summary) {
  std::vector<hil::RecordingUnit> units;
  std::map<std::string, std::string> recorded_kind;
  for (const hil::RecordingUnit& u : meta.units) {
    const std::string& serial = u.serial;
    const std::string kind = u.kind ? common::UnitKindName(*u.kind) : "";
    recorded_kind[serial] = kind;
    const auto f = files.find(serial);
    if (f == files.end()) {
      summary.skipped.push_back(serial);
      continue;
    }
    if (f->second.kind != kind) {
      throw std::runtime_error(fmt::format("{}: kind '{}' but {} is an {} unit in {}",
                                           f->second.path.string(),
                                           f->second.kind,
                                           serial,
                                           kind,
                                           (run_dir / "meta.json").string()));
    }
    units.push_back(u);
    summary.replayed.push_back(serial);
  }
  for (const auto& [serial, f] : files) {
    if (recorded_kind.count(serial) == 0) {
      std::string held;
      for (const auto& [s, k] : recorded_kind) held += (held.empty() ? "" : ", ") + s;
      throw std::runtime_error(fmt::format("{}: unit {} is not in {} (it holds {})",
                                           f.path.string(),
                                           serial,
                                           (run_dir / "meta.json").string(),
                                           held.empty() ? "none" : held));
    }
  }
  return units;
}

// What drives each unit: its model parameters and noise seed, and the IMU's gravity in g.
struct UnitModels {
  std::map<std::string, sensor_sim::ImuUnitParams> imu_params;
  std::map<std::string, sensor_sim::AdsUnitParams> ads_params;
  std::map<std::string, uint64_t> noise_seeds;
  double g_ratio = 1.0;  ///< local gravity / standard gravity
};

UnitModels LoadUnitModels(const std::map<std::string, UnitFile>& files,
                          const ReplayOptions& options,
                          const hil::RecordingMeta& meta,
                          const fs::path& run_dir) {
  UnitModels m;
  bool any_imu = false;
  for (const auto& [serial, f] : files) {
    if (options.noise_from_unit_file && !f.seed) {
      throw std::runtime_error(
          f.path.string() +
          ": $.seed: missing (the same noise as the rig needs a truth file's seed)");
    }
    m.noise_seeds[serial] = options.noise_from_unit_file
                                ? common::Rng::Derive(*f.seed, kNoiseStream)
                                : common::Rng::Derive(options.noise_seed, SerialStream(serial));
    const common::ParamReader params(f.file["params"], f.path.string(), "$.params");
    if (f.kind == "imu") {
      m.imu_params.emplace(serial, sensor_sim::ImuUnitParams::FromJson(params));
      any_imu = true;
    } else {
      m.ads_params.emplace(serial, sensor_sim::AdsUnitParams::FromJson(params));
    }
  }
  m.g_ratio = any_imu ? LocalGravity(meta, run_dir) / common::kStandardGravity_mps2 : 1.0;
  return m;
}

// meta.json (the recording's, with "replay" and only the replayed units) and truth/<serial>.json.
void WriteReplayMeta(hil::RecordingWriter& writer,
                     const hil::RecordingMeta& meta,
                     const std::vector<hil::RecordingUnit>& units,
                     const std::map<std::string, UnitFile>& files,
                     const fs::path& run_dir,
                     const fs::path& out_dir,
                     const ReplayOptions& options) {
  hil::RecordingMeta out_meta = meta;
  out_meta.units = units;
  out_meta.has_units = true;
  nlohmann::json file_list = nlohmann::json::array();
  for (const auto& [serial, f] : files) file_list.push_back(fs::absolute(f.path).string());
  out_meta.extra["replay"] = {
      {"of", fs::absolute(run_dir).string()},
      {"noise",
       options.noise_from_unit_file ? nlohmann::json("the unit files' seeds")
                                    : nlohmann::json(options.noise_seed)},
      {"unit_files", file_list}};
  writer.WriteMeta(out_meta);
  fs::create_directories(out_dir / "truth");
  for (const auto& [serial, f] : files) {
    WriteJsonFile(out_dir / "truth" / (serial + ".json"), f.file);
  }
}

// Writes the replayed rows: each row's unit, powered on at its first row, stepped over the frames
// the row spans with the row's stimulus; the row takes the last frame's raw outputs. `first` is the
// first reporting row of the file when `row` was held before it (LeadingZeros), else null.
class RowReplayer {
 public:
  RowReplayer(const UnitModels& models,
              const fs::path& run_dir,
              hil::RecordingWriter& writer,
              ReplaySummary& summary)
      : models_(models),
        imu_csv_(hil::StoredCsvPath(run_dir, hil::kImuCsvName).string()),
        ads_csv_(hil::StoredCsvPath(run_dir, hil::kAdsCsvName).string()),
        writer_(writer),
        summary_(summary) {}

  void Imu(hil::ImuRecordRow&& row, int line, const hil::ImuRecordRow* first) {
    const auto p = models_.imu_params.find(row.unit);
    if (p == models_.imu_params.end()) return;
    auto it = imus_.find(row.unit);
    const double air_c =
        first != nullptr && row.chamber_c == 0.0 ? first->chamber_c : row.chamber_c;
    if (it == imus_.end()) {
      ImuReplayer fresh{sensor_sim::ImuUnit(p->second, models_.noise_seeds.at(row.unit), air_c),
                        FrameClock(p->second.frame_period_s, imu_csv_ + " (" + row.unit + ")"),
                        {},
                        {}};
      it = imus_.emplace(row.unit, std::move(fresh)).first;
    }
    ImuReplayer& r = it->second;
    if (IsValidOrientation(row.orientation)) r.up_B = UpAxis_B(row.orientation);
    sensor_sim::ImuStimulus in;
    in.f_B_g = r.up_B * models_.g_ratio;
    in.w_B_dps = r.up_B * row.table_rate_dps;
    in.air_temp_c = air_c;
    for (int64_t n = r.clock.FramesFor(row.t_s, row.seq, row.frame, line); n > 0; --n) {
      r.last = r.unit.Step(in);
    }
    const sensor_sim::ImuRawFrame& f = r.last;
    for (size_t ch = 0; ch < 6; ++ch) {
      row.accel_ticks[2 * ch] = f.accel[ch].t1_cnt;
      row.accel_ticks[2 * ch + 1] = f.accel[ch].t2_cnt;
    }
    row.gyro_cnt = f.gyro_cnt;
    row.temp_cnt = f.temp_cnt;
    row.mode = 0;
    row.comp.reset();
    row.comp_flags = 0;
    writer_.Append(row);
    ++summary_.imu_rows;
  }

  void Ads(hil::AdsRecordRow&& row, int line, const hil::AdsRecordRow* first) {
    const auto p = models_.ads_params.find(row.unit);
    if (p == models_.ads_params.end()) return;
    const double air_c =
        first != nullptr && row.chamber_c == 0.0 ? first->chamber_c : row.chamber_c;
    auto it = adss_.find(row.unit);
    if (it == adss_.end()) {
      AdsReplayer fresh{sensor_sim::AdsUnit(p->second, models_.noise_seeds.at(row.unit), air_c),
                        FrameClock(p->second.frame_period_s, ads_csv_ + " (" + row.unit + ")"),
                        {}};
      it = adss_.emplace(row.unit, std::move(fresh)).first;
    }
    sensor_sim::AdsStimulus in;
    in.ps_pa = first != nullptr ? first->ps_ref_pa : row.ps_ref_pa;
    in.qc_pa = first != nullptr ? first->qc_ref_pa : row.qc_ref_pa;
    in.air_temp_c = air_c;
    in.oat_c = air_c;
    AdsReplayer& r = it->second;
    for (int64_t n = r.clock.FramesFor(row.t_s, row.seq, row.frame, line); n > 0; --n) {
      r.last = r.unit.Step(in);
    }
    const sensor_sim::AdsRawFrame& f = r.last;
    row.ps_cnt = f.ps_cnt;
    row.pt_cnt = f.pt_cnt;
    row.ps_temp_cnt = f.ps_temp_cnt;
    row.pt_temp_cnt = f.pt_temp_cnt;
    row.oat_cnt = f.oat_cnt;
    row.mode = 0;
    row.alt_ft.reset();
    row.cas_kt.reset();
    row.comp_flags = 0;
    writer_.Append(row);
    ++summary_.ads_rows;
  }

 private:
  const UnitModels& models_;
  const std::string imu_csv_;
  const std::string ads_csv_;
  hil::RecordingWriter& writer_;
  ReplaySummary& summary_;
  std::map<std::string, ImuReplayer> imus_;
  std::map<std::string, AdsReplayer> adss_;
};

}  // namespace

ReplaySummary ReplayRecording(const fs::path& run_dir,
                              const std::vector<fs::path>& unit_files,
                              const fs::path& out_dir,
                              const ReplayOptions& options) {
  const hil::Recording meta_only = hil::ReadRecordingMeta(run_dir);
  const hil::RecordingMeta& meta = meta_only.meta;
  const std::map<std::string, UnitFile> files = ReadUnitFiles(unit_files);
  ReplaySummary summary;
  const std::vector<hil::RecordingUnit> units = ReplayedUnits(meta, files, run_dir, summary);
  if (fs::exists(out_dir)) {
    throw std::runtime_error(out_dir.string() + ": exists; the replay writes a new run directory");
  }
  const UnitModels models = LoadUnitModels(files, options, meta, run_dir);

  hil::RecordingWriter writer(out_dir, options.storage);
  WriteReplayMeta(writer, meta, units, files, run_dir, out_dir, options);
  RowReplayer replayer(models, run_dir, writer, summary);
  auto emit_imu = [&](hil::ImuRecordRow&& row, int line, const hil::ImuRecordRow* first) {
    replayer.Imu(std::move(row), line, first);
  };
  auto emit_ads = [&](hil::AdsRecordRow&& row, int line, const hil::AdsRecordRow* first) {
    replayer.Ads(std::move(row), line, first);
  };

  // Reported: an IMU row once the chamber reads other than 0 or the fixture holds a code (after
  // that, 0 °C is a temperature); an ADS row once the test set reads a static pressure (never 0).
  LeadingZeros<hil::ImuRecordRow> imu_hold(
      [](const hil::ImuRecordRow& r) { return r.chamber_c != 0.0 || r.orientation != 0; });
  LeadingZeros<hil::AdsRecordRow> ads_hold(
      [](const hil::AdsRecordRow& r) { return r.ps_ref_pa != 0.0; });
  hil::RowSinks sinks;
  sinks.imu = [&](hil::ImuRecordRow&& row, int line) {
    if (models.imu_params.count(row.unit) != 0) imu_hold.Add(std::move(row), line, emit_imu);
  };
  sinks.ads = [&](hil::AdsRecordRow&& row, int line) {
    if (models.ads_params.count(row.unit) != 0) ads_hold.Add(std::move(row), line, emit_ads);
  };
  hil::StreamRecording(run_dir, sinks);
  imu_hold.Release(emit_imu);
  ads_hold.Release(emit_ads);
  writer.Flush(true);
  return summary;
}

}  // namespace adahrs::rig_sim
