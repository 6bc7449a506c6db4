// The production records database schema (docs/records.md) and its migrations. The schema_version
// table holds one row, the version applied; each migration is SQL that takes version n-1 to n and
// runs in one transaction with the version bump, so a database is always at a known version.
// A database newer than this program (a version beyond kRecordsSchemaVersion) is refused.
// Left out: down-migrations (records are only ever added to).
#pragma once

#include "calib/records/sqlite_database.h"

namespace adahrs::calib {

inline constexpr int kRecordsSchemaVersion = 3;

/// The version the database is at (0 for a new, empty file).
int RecordsSchemaVersionOf(SqliteDatabase& database);

/// Applies every migration the database has not had; throws RecordsError naming the file and the
/// migration if one fails (that migration is rolled back), or if the database is newer than us.
void MigrateRecordsSchema(SqliteDatabase& database);

/// For a reader that must not write: throws RecordsError naming the file unless it holds the
/// records schema of this program's version (an empty file, another SQLite database, an older or
/// a newer schema are refused; an older one is migrated by any command that writes).
void RequireRecordsSchema(SqliteDatabase& database);

}  // namespace adahrs::calib
