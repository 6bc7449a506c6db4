#include "calib/records/records_schema.h"

#include <string_view>

#include <fmt/format.h>

namespace adahrs::calib {
namespace {

// Migration i takes the schema from version i to i + 1.
// Constants rows are evidence of what a unit was given: triggers refuse UPDATE and DELETE, so a
// version once recorded is never overwritten; a new fit is a new version.
constexpr std::string_view kMigrations[] = {
    R"sql(
CREATE TABLE units (
  serial TEXT PRIMARY KEY,
  kind TEXT NOT NULL CHECK (kind IN ('imu', 'ads')),
  first_seen_utc TEXT NOT NULL
);
CREATE TABLE runs (
  id INTEGER PRIMARY KEY,
  run_id TEXT NOT NULL,
  run_dir TEXT NOT NULL,
  sequence_name TEXT NOT NULL,
  sequence_file TEXT NOT NULL,
  station_name TEXT NOT NULL,
  started_utc TEXT NOT NULL,
  status TEXT NOT NULL,
  recording_sha256 TEXT NOT NULL,
  meta_json TEXT NOT NULL,
  recorded_utc TEXT NOT NULL,
  UNIQUE (run_id, recording_sha256)
);
CREATE TABLE run_units (
  run INTEGER NOT NULL REFERENCES runs(id),
  serial TEXT NOT NULL REFERENCES units(serial),
  role TEXT NOT NULL,
  slot INTEGER NOT NULL,
  firmware TEXT NOT NULL,
  constants_version INTEGER,
  mode INTEGER NOT NULL,
  PRIMARY KEY (run, serial)
);
CREATE TABLE steps (
  run INTEGER NOT NULL REFERENCES runs(id),
  step_index INTEGER NOT NULL,
  kind TEXT NOT NULL,
  tag INTEGER NOT NULL,
  rejected_s REAL NOT NULL,
  PRIMARY KEY (run, step_index)
);
CREATE TABLE constants (
  id INTEGER PRIMARY KEY,
  serial TEXT NOT NULL REFERENCES units(serial),
  version INTEGER NOT NULL,
  strategy TEXT NOT NULL,
  created_utc TEXT NOT NULL,
  software_version TEXT NOT NULL,
  file_sha256 TEXT NOT NULL,
  json TEXT NOT NULL,
  provenance_json TEXT NOT NULL,
  recorded_utc TEXT NOT NULL,
  UNIQUE (serial, version),
  UNIQUE (serial, file_sha256)
);
CREATE TRIGGER constants_never_updated BEFORE UPDATE ON constants
  BEGIN SELECT RAISE(ABORT, 'constants versions are never overwritten'); END;
CREATE TRIGGER constants_never_deleted BEFORE DELETE ON constants
  BEGIN SELECT RAISE(ABORT, 'constants versions are never deleted'); END;
CREATE TABLE downloads (
  id INTEGER PRIMARY KEY,
  constants INTEGER NOT NULL REFERENCES constants(id),
  downloaded_utc TEXT NOT NULL,
  station_name TEXT NOT NULL,
  role TEXT NOT NULL,
  verified INTEGER NOT NULL,
  committed INTEGER NOT NULL,
  unit_constants_version INTEGER,
  unit_constants_crc INTEGER,
  detail TEXT NOT NULL
);
CREATE TABLE acceptance_results (
  id INTEGER PRIMARY KEY,
  serial TEXT NOT NULL REFERENCES units(serial),
  source_sha256 TEXT NOT NULL,
  run_id TEXT NOT NULL,
  quantity TEXT NOT NULL,
  condition TEXT NOT NULL,
  error REAL NOT NULL,
  tolerance REAL NOT NULL,
  unit TEXT NOT NULL,
  pass INTEGER NOT NULL,
  recorded_utc TEXT NOT NULL
);
CREATE INDEX acceptance_by_unit ON acceptance_results(serial, source_sha256);
)sql",
    // Version 2: which specification file each point was judged against (its SHA-256) and the
    // point's outcome. Points recorded before were judged without a marginal band: their outcome
    // is PASS or FAIL as `pass` says; their specification is not known ('').
    R"sql(
ALTER TABLE acceptance_results ADD COLUMN specification_sha256 TEXT NOT NULL DEFAULT '';
ALTER TABLE acceptance_results ADD COLUMN outcome TEXT NOT NULL DEFAULT '';
UPDATE acceptance_results SET outcome = CASE pass WHEN 1 THEN 'PASS' ELSE 'FAIL' END;
)sql",
    // Version 3: each unit's acceptance attempts in a campaign (first pass, retests), from which
    // first-pass and final yield are counted (yield_records.h).
    R"sql(
CREATE TABLE acceptance_attempts (
  campaign TEXT NOT NULL,
  serial TEXT NOT NULL REFERENCES units(serial),
  role TEXT NOT NULL,
  attempt INTEGER NOT NULL CHECK (attempt >= 1),
  run_id TEXT NOT NULL,
  source_sha256 TEXT NOT NULL,
  outcome TEXT NOT NULL CHECK (outcome IN ('PASS', 'MARGINAL', 'FAIL')),
  recorded_utc TEXT NOT NULL,
  PRIMARY KEY (campaign, serial, attempt)
);
CREATE TRIGGER acceptance_attempts_never_updated BEFORE UPDATE ON acceptance_attempts
BEGIN SELECT RAISE(ABORT, 'acceptance attempts are never updated'); END;
CREATE TRIGGER acceptance_attempts_never_deleted BEFORE DELETE ON acceptance_attempts
BEGIN SELECT RAISE(ABORT, 'acceptance attempts are never deleted'); END;
)sql",
};

static_assert(std::size(kMigrations) == kRecordsSchemaVersion);

}  // namespace

int RecordsSchemaVersionOf(SqliteDatabase& database) {
  SqliteStatement exists(database,
                         "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND "
                         "name = 'schema_version'");
  exists.Step();
  if (exists.Int(0) == 0) return 0;
  SqliteStatement version(database, "SELECT version FROM schema_version");
  if (!version.Step()) return 0;
  return static_cast<int>(version.Int(0));
}

void RequireRecordsSchema(SqliteDatabase& database) {
  const int found = RecordsSchemaVersionOf(database);
  if (found == 0) {
    throw RecordsError(
        fmt::format("records database {}: not an adahrs records database (no schema_version)",
                    database.file().string()));
  }
  if (found != kRecordsSchemaVersion) {
    throw RecordsError(fmt::format(
        "records database {}: schema version {}, this program reads {}{}",
        database.file().string(),
        found,
        kRecordsSchemaVersion,
        found < kRecordsSchemaVersion ? " (a records command that writes migrates it)" : ""));
  }
}

void MigrateRecordsSchema(SqliteDatabase& database) {
  SqliteTransaction bootstrap(database);
  database.Execute("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
  SqliteStatement count(database, "SELECT count(*) FROM schema_version");
  count.Step();
  if (count.Int(0) == 0) database.Execute("INSERT INTO schema_version VALUES (0)");
  bootstrap.Commit();

  const int found = RecordsSchemaVersionOf(database);
  if (found > kRecordsSchemaVersion) {
    throw RecordsError(fmt::format(
        "records database {}: schema version {} is newer than this program's ({}); use a newer "
        "adahrs",
        database.file().string(),
        found,
        kRecordsSchemaVersion));
  }
  for (int version = found; version < kRecordsSchemaVersion; ++version) {
    SqliteTransaction transaction(database);
    try {
      database.Execute(kMigrations[version]);
    } catch (const RecordsError& e) {
      throw RecordsError(fmt::format("migration to schema version {}: {}", version + 1, e.what()));
    }
    SqliteStatement(database, "UPDATE schema_version SET version = ?")
        .Bind(1, int64_t{version + 1})
        .Run();
    transaction.Commit();
  }
}

}  // namespace adahrs::calib
