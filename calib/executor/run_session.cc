#include "calib/executor/run_session.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/executor/journal.h"
#include "calib/executor/offset_clock.h"
#include "calib/executor/resume_point.h"
#include "calib/executor/run_lock.h"
#include "calib/executor/run_meta.h"
#include "calib/executor/unit_logger.h"
#include "calib/sequence/sequence_json.h"
#include "calib/sequence/station_limits.h"
#include "calib/sequence/validation.h"
#include "hil/drivers/station_instruments.h"
#include "hil/drivers/unit_serial.h"
#include "hil/instruments/instrument_error.h"
#include "hil/recording/csv_lines.h"
#include "hil/recording/recording_files.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"
#include "hil/recording/torn_tail.h"
#include "hil/utc_time.h"

namespace adahrs::calib {
namespace {

constexpr const char* kTimeBase =
    "pipeline clock seconds since the run started (simulated seconds on a scaled rig)";

// The t_s of the last complete row of a CSV, plain or compressed (0 when it has none); a cell
// that is not a time of the run is refused naming the file and line.
double LastRowTime(const std::filesystem::path& csv) {
  if (!std::filesystem::exists(csv)) return 0.0;
  hil::CsvLines lines(csv);
  std::string_view line;
  bool complete = false;
  std::string last;
  long line_number = 0, last_number = 0;
  while (lines.Next(line, complete)) {
    ++line_number;
    if (line_number > 1 && complete && !line.empty()) {
      last = line;
      last_number = line_number;
    }
  }
  if (last.empty()) return 0.0;
  const std::string cell = last.substr(0, last.find(','));
  double t_s = 0.0;
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), t_s);
  constexpr double kMaxRunTime_s = 365.0 * 86400.0;  // as the journal's (resume_point.cc)
  if (ec != std::errc() || end != cell.data() + cell.size() ||
      !(t_s >= 0.0 && t_s <= kMaxRunTime_s)) {
    throw std::runtime_error(
        fmt::format("{}:{}: column 1 (t_s) '{}' is not a time of the run: the last complete "
                    "row is corrupt, so the run cannot be resumed after it",
                    csv.string(),
                    last_number,
                    cell));
  }
  return t_s;
}

// The stored CSV of `csv_name` (plain or compressed: a resumed run keeps its form); both forms
// present is refused before anything moves.
std::filesystem::path StoredCsv(const std::filesystem::path& run_dir, std::string_view csv_name) {
  try {
    return hil::StoredCsvPath(run_dir, csv_name);
  } catch (const std::runtime_error& e) {
    throw RunError(e.what());
  }
}

// Everything a run needs once the station, the sequence and the run directory are decided.
struct Session {
  hil::Station station;
  Sequence sequence;
  ExecutionPlan plan;
  std::filesystem::path run_dir;
  std::string sequence_file;
};

// The station's units of the sequence's kind: the batch, 1 to 4 of them for IMUs.
std::vector<hil::UnitLink*> BatchLinks(const hil::StationInstruments& instruments,
                                       const Session& s) {
  const bool imu_batch = s.sequence.unit_kind == UnitKind::kImu;
  std::vector<hil::UnitLink*> links;
  for (const auto& link : instruments.units) {
    if (link->entry().kind == s.sequence.unit_kind) links.push_back(link.get());
  }
  if (links.empty() || (imu_batch && links.size() > 4)) {
    throw RunError(fmt::format("station '{}' has {} {} units; a batch is 1 to {} of them",
                               s.station.name,
                               links.size(),
                               UnitKindName(s.sequence.unit_kind),
                               imu_batch ? "4" : "any number"));
  }
  return links;
}

// What the units say of themselves: meta.json's $.units and their serials, in batch order.
struct BatchUnits {
  std::vector<hil::RecordingUnit> units;
  std::vector<std::string> serials;
};

BatchUnits IdentifyUnits(const std::vector<hil::UnitLink*>& links, bool imu_batch) {
  BatchUnits out;
  for (hil::UnitLink* link : links) {
    const hil::IdentifyInfo id = link->Identify();
    const std::string serial = hil::UnitSerialText(link->entry().kind, id.serial_number);
    out.serials.push_back(serial);
    hil::RecordingUnit u;
    u.role = link->entry().role;
    u.kind = imu_batch ? hil::UnitKind::kImu : hil::UnitKind::kAds;
    u.serial = serial;
    u.serial_number = id.serial_number;
    u.firmware = fmt::format("{}.{}.{}", id.firmware_major, id.firmware_minor, id.firmware_patch);
    u.slot = link->entry().slot;
    u.constants_version = id.constants_version;
    u.mode = id.mode;
    if (const std::optional<hil::LineTiming> line = link->line_timing()) {
      u.line_buffering_s = line->buffering_s;
      u.clock_drift_ppm = line->drift_ppm;
    }
    out.units.push_back(std::move(u));
  }
  return out;
}

// The instruments an IMU batch uses (rate table, IMU chamber) or an ADS batch (ADS chamber, ADTS).
BatchInstruments BatchInstrumentsFor(const hil::StationInstruments& instruments, bool imu_batch) {
  BatchInstruments batch{instruments.rate_table.get(),
                         imu_batch ? instruments.imu_chamber.get() : instruments.ads_chamber.get(),
                         instruments.adts.get(),
                         instruments.op.get()};
  if (!imu_batch) batch.rate_table = nullptr;
  if (imu_batch) batch.adts = nullptr;
  return batch;
}

// meta.json's $.instruments: what each instrument of the batch says it is.
std::vector<hil::RecordingInstrument> IdentifyInstruments(const BatchInstruments& batch,
                                                          bool imu_batch) {
  std::vector<hil::RecordingInstrument> identities;
  // A crashed predecessor's late replies on a line are the drivers' business (they flush and
  // repeat a garbled exchange within their bounded retries).
  const auto identify = [&](const char* role, auto* instrument) {
    if (instrument == nullptr) return;
    const hil::InstrumentIdentity id = instrument->Identify();
    identities.push_back({role, id.model, id.detail});
  };
  identify("rate_table", batch.rate_table);
  identify(imu_batch ? "imu_chamber" : "ads_chamber", batch.chamber);
  identify("adts", batch.adts);
  return identities;
}

// The interrupted run's meta, refused when the batch is not the same units in the same order.
hil::RecordingMeta ResumedRunMeta(hil::RecordingMeta meta,
                                  const Session& s,
                                  const std::vector<hil::UnitLink*>& links,
                                  const std::vector<std::string>& serials) {
  for (size_t u = 0; u < serials.size(); ++u) {
    const std::vector<hil::RecordingUnit>& old_units = meta.units;
    if (old_units.size() != serials.size() || old_units[u].serial != serials[u]) {
      throw RunError(fmt::format(
          "{}: the batch differs from the interrupted run's: {} is now {}, was {}",
          (s.run_dir / hil::kMetaJsonName).string(),
          links[u]->entry().role,
          serials[u],
          u < old_units.size() ? nlohmann::json(old_units[u].serial).dump() : "absent"));
    }
  }
  return meta;
}

hil::RecordingMeta NewRunMeta(const Session& s, const std::vector<hil::RecordingUnit>& units) {
  hil::RecordingMeta m;
  m.format_version = hil::kRecordingFormatVersion;
  m.run_id = s.run_dir.filename().string() + "-" + hil::UtcNowIso8601();
  m.started_utc = hil::UtcNowIso8601();
  m.station = s.station.ToJson();
  m.sequence = SequenceToJson(s.sequence);
  m.sequence_file = s.sequence_file;
  m.time_base = kTimeBase;
  m.sample_rate_hz = 100.0;
  m.local_gravity_mps2 = s.station.local_gravity_mps2;
  m.units = units;
  m.has_units = true;
  m.has_rejected_intervals = true;
  return m;
}

// The run's meta as it starts: new, or the interrupted run's; either way running, with the
// instruments of this session.
hil::RecordingMeta StartingRunMeta(const Session& s,
                                   const hil::Clock& clock,
                                   const std::optional<hil::RecordingMeta>& old_meta,
                                   const std::vector<hil::UnitLink*>& links,
                                   const BatchUnits& units,
                                   std::vector<hil::RecordingInstrument> identities) {
  hil::RecordingMeta meta =
      old_meta ? ResumedRunMeta(*old_meta, s, links, units.serials) : NewRunMeta(s, units.units);
  meta.instruments = std::move(identities);
  meta.status = kStatusRunning;
  // The resumed clock continues from the last recorded time: the frames the units ran meanwhile
  // shift the sample times from here (hil/recording/sample_time_check.h).
  if (old_meta) meta.resumed_t_s.push_back(clock.NowS());
  return meta;
}

// The journal's first events of this session: the run started or resumed, then what resuming
// found (each at the clock's time now).
void JournalSessionStart(Journal& journal,
                         const hil::Clock& clock,
                         bool resumed,
                         size_t first_step,
                         std::vector<TornTailSetAside> resume_events) {
  journal.Append(RunStarted{clock.NowS(), hil::UtcNowIso8601(), first_step, resumed});
  for (TornTailSetAside& e : resume_events) {
    e.t_s = clock.NowS();
    journal.Append(e);
  }
  journal.Sync();
}

std::vector<std::unique_ptr<UnitLogger>> StartUnitLoggers(const std::vector<hil::UnitLink*>& links,
                                                          const std::vector<std::string>& serials,
                                                          SharedRecording& recording,
                                                          RunAnnotations& annotations) {
  std::vector<std::unique_ptr<UnitLogger>> loggers;
  for (size_t u = 0; u < links.size(); ++u) {
    loggers.push_back(std::make_unique<UnitLogger>(*links[u], serials[u], recording, annotations));
    loggers.back()->Start();
  }
  return loggers;
}

std::vector<UnitLogger*> Pointers(const std::vector<std::unique_ptr<UnitLogger>>& loggers) {
  std::vector<UnitLogger*> out;
  for (const auto& l : loggers) out.push_back(l.get());
  return out;
}

RunSummary Execute(const Session& s,
                   const hil::Clock& clock,
                   std::optional<hil::RecordingMeta> old_meta,
                   size_t first_step,
                   std::optional<double> repeated_from_s,
                   std::vector<TornTailSetAside> resume_events,
                   ProgressSink& progress,
                   const std::atomic<bool>& stop,
                   const NewRunOptions& options) {
  ExecutorOptions executor_options = options.executor;
  executor_options.interlock_thresholds =
      ThresholdsForStation(s.station, executor_options.interlock_thresholds);
  executor_options.interlock_attempts =
      InterlockAttemptsForStation(s.station, executor_options.interlock_attempts);
  hil::StationInstruments instruments = hil::OpenStation(s.station, clock);
  if (options.wrap_operator) instruments.op = options.wrap_operator(std::move(instruments.op));
  const bool imu_batch = s.sequence.unit_kind == UnitKind::kImu;
  const std::vector<hil::UnitLink*> links = BatchLinks(instruments, s);
  const BatchUnits units = IdentifyUnits(links, imu_batch);
  const BatchInstruments batch = BatchInstrumentsFor(instruments, imu_batch);
  hil::RecordingMeta meta =
      StartingRunMeta(s, clock, old_meta, links, units, IdentifyInstruments(batch, imu_batch));

  hil::RecordingWriter writer(s.run_dir, options.storage);
  SharedRecording recording(writer);
  RunMeta run_meta(std::move(meta), recording);
  run_meta.Write();
  Journal journal(s.run_dir);
  JournalSessionStart(journal, clock, old_meta.has_value(), first_step, std::move(resume_events));

  RunAnnotations annotations;
  const std::vector<std::unique_ptr<UnitLogger>> loggers =
      StartUnitLoggers(links, units.serials, recording, annotations);
  Executor executor(s.sequence,
                    s.plan,
                    batch,
                    Pointers(loggers),
                    clock,
                    annotations,
                    recording,
                    journal,
                    run_meta,
                    progress,
                    stop,
                    executor_options);
  const auto summary = [&] {
    RunSummary out{s.run_dir, run_meta.meta().status.value_or(""), 0, 0};
    for (auto& l : loggers) {
      l->Stop();
      out.rows += l->rows();
      out.lost += l->lost();
    }
    recording.Flush(true);
    return out;
  };
  try {
    executor.Run(first_step, repeated_from_s);
  } catch (...) {
    summary();
    throw;
  }
  return summary();
}

}  // namespace

RunSummary StartRun(const NewRunOptions& options,
                    ProgressSink& progress,
                    const std::atomic<bool>& stop) {
  Session s;
  s.station = hil::Station::Load(options.station_file);
  const SequenceLimits limits = LimitsForStation(s.station);
  s.sequence = LoadValidSequence(options.sequence_file, limits);
  s.plan = ExpandSequence(s.sequence, limits, TimingForStation(s.station, s.sequence.unit_kind));
  s.run_dir = options.run_dir;
  s.sequence_file = options.sequence_file;
  if (std::filesystem::exists(s.run_dir / hil::kMetaJsonName)) {
    throw RunError(fmt::format("{} already holds a run; resume it with adahrs run --resume {}",
                               s.run_dir.string(),
                               s.run_dir.string()));
  }
  std::filesystem::create_directories(s.run_dir);
  const RunDirectoryLock lock(s.run_dir);
  const std::unique_ptr<hil::Clock> clock =
      hil::MakeClock(s.station.time_scale, s.station.clock_file);
  return Execute(s, *clock, std::nullopt, 0, std::nullopt, {}, progress, stop, options);
}

RunSummary ResumeRun(const std::filesystem::path& run_dir,
                     ProgressSink& progress,
                     const std::atomic<bool>& stop,
                     const NewRunOptions& options) {
  const std::filesystem::path meta_path = run_dir / hil::kMetaJsonName;
  if (!std::filesystem::exists(meta_path))
    throw RunError(meta_path.string() + ": no run to resume here");
  const RunDirectoryLock lock(run_dir);  // before anything of the run is read or moved
  const hil::RecordingMeta meta = hil::ReadRecordingMeta(run_dir).meta;
  if (meta.format_version != hil::kRecordingFormatVersion || !meta.station || !meta.sequence) {
    throw RunError(meta_path.string() + ": not an executor run of recording format version " +
                   std::to_string(hil::kRecordingFormatVersion) + " ($.station, $.sequence)");
  }
  Session s;
  s.station =
      hil::Station::FromJson(common::ParamReader(*meta.station, meta_path.string(), "$.station"));
  const SequenceLimits limits = LimitsForStation(s.station);
  s.sequence = SequenceFromJson(*meta.sequence, meta_path.string() + " $.sequence");
  s.plan = ExpandSequence(s.sequence, limits, TimingForStation(s.station, s.sequence.unit_kind));
  s.run_dir = run_dir;

  std::vector<TornTailSetAside> events;
  const std::filesystem::path imu_csv = StoredCsv(run_dir, hil::kImuCsvName);
  const std::filesystem::path ads_csv = StoredCsv(run_dir, hil::kAdsCsvName);
  for (const std::filesystem::path& file : {imu_csv, ads_csv, run_dir / kJournalName}) {
    if (const auto torn = hil::SetAsideTornTail(file)) {
      events.push_back({0.0, file.filename().string(), torn->filename().string()});
      progress.Note(fmt::format("torn last line of {} moved to {}", file.string(), torn->string()));
    }
  }
  const ResumePoint point = FindResumePoint(ReadJournal(run_dir), s.sequence.steps.size());
  if (point.run_completed || point.first_incomplete_step >= s.sequence.steps.size()) {
    throw RunError(run_dir.string() + ": the run is complete; nothing to resume");
  }
  // The clock continues one packet period after the latest time on record.
  const double last_t_s = std::max({point.last_t_s, LastRowTime(imu_csv), LastRowTime(ads_csv)});
  const std::unique_ptr<hil::Clock> base =
      hil::MakeClock(s.station.time_scale, s.station.clock_file);
  const OffsetClock clock(*base, last_t_s + 1.0 / options.executor.packet_rate_hz);
  progress.Note(fmt::format("resuming {} at step {} of {}, clock from t = {:.2f} s",
                            run_dir.string(),
                            point.first_incomplete_step + 1,
                            s.sequence.steps.size(),
                            clock.NowS()));
  return Execute(s,
                 clock,
                 meta,
                 point.first_incomplete_step,
                 point.interrupted_step_started_s,
                 std::move(events),
                 progress,
                 stop,
                 options);
}

}  // namespace adahrs::calib
