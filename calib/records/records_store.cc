#include "calib/records/records_store.h"

#include <fmt/format.h>

#include "calib/constants/constants_file.h"
#include "calib/records/records_schema.h"
#include "common/printable_text.h"

namespace adahrs::calib {
namespace {

// The kind a serial text names (unit_serial.h: "IMU-%04u" / "ADS-%04u").
std::string KindOfSerial(const std::filesystem::path& file, const std::string& serial) {
  if (serial.rfind("IMU-", 0) == 0) return "imu";
  if (serial.rfind("ADS-", 0) == 0) return "ads";
  throw RecordsError(fmt::format("records database {}: unit serial '{}' is neither IMU-… nor ADS-…",
                                 file.string(),
                                 common::PrintableText(serial)));
}

}  // namespace

RecordsStore::RecordsStore(const std::filesystem::path& file) : database_(file, true) {
  MigrateRecordsSchema(database_);
}

RecordsStore::RecordsStore(const std::filesystem::path& file, ReadOnly)
    : database_(file, false, true) {
  RequireRecordsSchema(database_);
}

RecordsStore RecordsStore::OpenForReading(const std::filesystem::path& file) {
  return RecordsStore(file, ReadOnly{});
}

void RecordsStore::EnsureUnit(const std::string& serial, const std::string& kind) {
  if (KindOfSerial(database_.file(), serial) != kind) {
    throw RecordsError(fmt::format(
        "records database {}: unit {} given kind '{}', but its serial names another kind",
        database_.file().string(),
        serial,
        kind));
  }
  SqliteStatement(database_,
                  "INSERT OR IGNORE INTO units (serial, kind, first_seen_utc) VALUES (?, ?, ?)")
      .Bind(1, serial)
      .Bind(2, kind)
      .Bind(3, UtcNowIso8601())
      .Run();
}

void RecordsStore::EnsureUnit(const std::string& serial) {
  EnsureUnit(serial, KindOfSerial(database_.file(), serial));
}

bool RecordsStore::AddRun(const RunRecord& run) {
  SqliteTransaction transaction(database_);
  SqliteStatement existing(database_,
                           "SELECT id FROM runs WHERE run_id = ? AND recording_sha256 = ?");
  existing.Bind(1, run.run_id).Bind(2, run.recording_sha256);
  if (existing.Step()) return false;
  SqliteStatement(database_,
                  "INSERT INTO runs (run_id, run_dir, sequence_name, sequence_file, station_name, "
                  "started_utc, status, recording_sha256, meta_json, recorded_utc) "
                  "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)")
      .Bind(1, run.run_id)
      .Bind(2, run.run_dir)
      .Bind(3, run.sequence_name)
      .Bind(4, run.sequence_file)
      .Bind(5, run.station_name)
      .Bind(6, run.started_utc)
      .Bind(7, run.status)
      .Bind(8, run.recording_sha256)
      .Bind(9, run.meta_json)
      .Bind(10, UtcNowIso8601())
      .Run();
  const int64_t run_row = database_.LastInsertRowId();
  for (const RunUnitRecord& unit : run.units) {
    EnsureUnit(unit.serial, unit.kind);
    SqliteStatement(database_,
                    "INSERT INTO run_units (run, serial, role, slot, firmware, constants_version, "
                    "mode) VALUES (?, ?, ?, ?, ?, ?, ?)")
        .Bind(1, run_row)
        .Bind(2, unit.serial)
        .Bind(3, unit.role)
        .Bind(4, int64_t{unit.slot})
        .Bind(5, unit.firmware)
        .Bind(6, unit.constants_version)
        .Bind(7, int64_t{unit.mode})
        .Run();
  }
  for (const StepRecord& step : run.steps) {
    SqliteStatement(
        database_,
        "INSERT INTO steps (run, step_index, kind, tag, rejected_s) VALUES (?, ?, ?, ?, ?)")
        .Bind(1, run_row)
        .Bind(2, int64_t{step.index})
        .Bind(3, step.kind)
        .Bind(4, int64_t{step.tag})
        .Bind(5, step.rejected_s)
        .Run();
  }
  transaction.Commit();
  return true;
}

std::optional<int64_t> RecordsStore::FindConstantsVersion(const std::string& serial,
                                                          const std::string& file_sha256) {
  SqliteStatement find(database_,
                       "SELECT version FROM constants WHERE serial = ? AND file_sha256 = ?");
  find.Bind(1, serial).Bind(2, file_sha256);
  if (!find.Step()) return std::nullopt;
  return find.Int(0);
}

int64_t RecordsStore::AddConstants(const ConstantsRecord& constants) {
  SqliteTransaction transaction(database_);
  if (const auto version = FindConstantsVersion(constants.serial, constants.file_sha256)) {
    return *version;
  }
  EnsureUnit(constants.serial, constants.kind);
  SqliteStatement next(database_,
                       "SELECT coalesce(max(version), 0) + 1 FROM constants WHERE serial = ?");
  next.Bind(1, constants.serial).Step();
  const int64_t version = next.Int(0);
  SqliteStatement(
      database_,
      "INSERT INTO constants (serial, version, strategy, created_utc, software_version, "
      "file_sha256, json, provenance_json, recorded_utc) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)")
      .Bind(1, constants.serial)
      .Bind(2, version)
      .Bind(3, constants.strategy)
      .Bind(4, constants.created_utc)
      .Bind(5, constants.software_version)
      .Bind(6, constants.file_sha256)
      .Bind(7, constants.json)
      .Bind(8, constants.provenance_json)
      .Bind(9, UtcNowIso8601())
      .Run();
  transaction.Commit();
  return version;
}

void RecordsStore::AddDownload(const DownloadRecord& download) {
  SqliteTransaction transaction(database_);
  SqliteStatement find(database_, "SELECT id FROM constants WHERE serial = ? AND version = ?");
  find.Bind(1, download.serial).Bind(2, download.constants_version);
  if (!find.Step()) {
    throw RecordsError(fmt::format("records database {}: unit {} has no constants version {}",
                                   database_.file().string(),
                                   download.serial,
                                   download.constants_version));
  }
  const int64_t constants_row = find.Int(0);
  SqliteStatement(database_,
                  "INSERT INTO downloads (constants, downloaded_utc, station_name, role, verified, "
                  "committed, unit_constants_version, unit_constants_crc, detail) "
                  "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)")
      .Bind(1, constants_row)
      .Bind(2, UtcNowIso8601())
      .Bind(3, download.station_name)
      .Bind(4, download.role)
      .Bind(5, int64_t{download.verified})
      .Bind(6, int64_t{download.committed})
      .Bind(7, download.unit_constants_version)
      .Bind(8, download.unit_constants_crc)
      .Bind(9, download.detail)
      .Run();
  transaction.Commit();
}

bool RecordsStore::AddAcceptance(const std::string& source_sha256,
                                 const std::vector<AcceptancePointRecord>& points) {
  SqliteTransaction transaction(database_);
  SqliteStatement existing(database_, "SELECT 1 FROM acceptance_results WHERE source_sha256 = ?");
  existing.Bind(1, source_sha256);
  if (existing.Step()) return false;
  const std::string now = UtcNowIso8601();
  for (const AcceptancePointRecord& point : points) {
    EnsureUnit(point.serial);
    SqliteStatement(database_,
                    "INSERT INTO acceptance_results (serial, source_sha256, run_id, quantity, "
                    "condition, error, tolerance, unit, pass, recorded_utc, outcome, "
                    "specification_sha256) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)")
        .Bind(1, point.serial)
        .Bind(2, source_sha256)
        .Bind(3, point.run_id)
        .Bind(4, point.quantity)
        .Bind(5, point.condition)
        .Bind(6, point.error)
        .Bind(7, point.tolerance)
        .Bind(8, point.unit)
        .Bind(9, int64_t{point.pass})
        .Bind(10, now)
        .Bind(11, point.outcome)
        .Bind(12, point.specification_sha256)
        .Run();
  }
  transaction.Commit();
  return true;
}

UnitHistory RecordsStore::History(const std::string& serial) {
  UnitHistory history;
  SqliteStatement unit(database_, "SELECT kind, first_seen_utc FROM units WHERE serial = ?");
  unit.Bind(1, serial);
  if (!unit.Step()) {
    throw RecordsError(
        fmt::format("records database {}: no unit {} recorded", database_.file().string(), serial));
  }
  history.serial = serial;
  history.kind = unit.Text(0);
  history.first_seen_utc = unit.Text(1);

  SqliteStatement runs(database_,
                       "SELECT r.run_id, r.run_dir, r.sequence_name, r.started_utc, r.status, "
                       "r.recording_sha256, u.role FROM runs r JOIN run_units u ON u.run = r.id "
                       "WHERE u.serial = ? ORDER BY r.started_utc, r.id");
  runs.Bind(1, serial);
  while (runs.Step()) {
    history.runs.push_back({runs.Text(0),
                            runs.Text(1),
                            runs.Text(2),
                            runs.Text(3),
                            runs.Text(4),
                            runs.Text(5),
                            runs.Text(6)});
  }

  SqliteStatement constants(
      database_,
      "SELECT c.version, c.strategy, c.created_utc, c.file_sha256, c.json, "
      "(SELECT count(*) FROM downloads d WHERE d.constants = c.id), "
      "(SELECT d.unit_constants_version FROM downloads d WHERE d.constants = c.id AND d.committed "
      " ORDER BY d.id DESC LIMIT 1), "
      "(SELECT d.unit_constants_crc FROM downloads d WHERE d.constants = c.id AND d.committed "
      " ORDER BY d.id DESC LIMIT 1), "
      "EXISTS (SELECT 1 FROM downloads d WHERE d.constants = c.id AND d.committed) "
      "FROM constants c WHERE c.serial = ? ORDER BY c.version");
  constants.Bind(1, serial);
  while (constants.Step()) {
    ConstantsVersion v;
    v.version = constants.Int(0);
    v.strategy = constants.Text(1);
    v.created_utc = constants.Text(2);
    v.file_sha256 = constants.Text(3);
    v.json = constants.Text(4);
    v.downloads = static_cast<int>(constants.Int(5));
    v.unit_constants_version = constants.OptionalInt(6);
    v.unit_constants_crc = constants.OptionalInt(7);
    v.committed = constants.Int(8) != 0;
    history.constants.push_back(std::move(v));
  }

  SqliteStatement acceptance(database_,
                             "SELECT run_id, source_sha256, quantity, condition, error, tolerance, "
                             "unit, pass, outcome, specification_sha256 FROM acceptance_results "
                             "WHERE serial = ? ORDER BY id");
  acceptance.Bind(1, serial);
  while (acceptance.Step()) {
    const std::string source = acceptance.Text(1);
    if (history.acceptance.empty() || history.acceptance.back().source_sha256 != source) {
      history.acceptance.push_back({acceptance.Text(0), source, 0, 0, 0, acceptance.Text(9), {}});
    }
    AcceptanceVerdict& verdict = history.acceptance.back();
    ++verdict.points;
    if (acceptance.Text(8) == "MARGINAL") ++verdict.marginal;
    if (acceptance.Int(7) == 0) {
      ++verdict.failed;
      verdict.failures.push_back({serial,
                                  acceptance.Text(0),
                                  acceptance.Text(2),
                                  acceptance.Text(3),
                                  acceptance.Real(4),
                                  acceptance.Real(5),
                                  acceptance.Text(6),
                                  false,
                                  acceptance.Text(8),
                                  acceptance.Text(9)});
    }
  }
  return history;
}

}  // namespace adahrs::calib
