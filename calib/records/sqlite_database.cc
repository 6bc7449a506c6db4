#include "calib/records/sqlite_database.h"

#include <sqlite3.h>

#include <fmt/format.h>

namespace adahrs::calib {

SqliteDatabase::SqliteDatabase(const std::filesystem::path& file, bool create, bool read_only)
    : file_(file) {
  if (!create && !std::filesystem::exists(file)) {
    throw RecordsError(fmt::format("records database {}: no such file", file.string()));
  }
  const int flags =
      read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
  if (sqlite3_open_v2(file.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string message = db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw RecordsError(fmt::format("records database {}: cannot open: {}", file.string(), message));
  }
  sqlite3_busy_timeout(db_, 5000);
  if (!read_only) Execute("PRAGMA foreign_keys = ON; PRAGMA journal_mode = WAL;");
}

SqliteDatabase::~SqliteDatabase() { sqlite3_close(db_); }

void SqliteDatabase::Execute(std::string_view sql) {
  char* error = nullptr;
  const std::string text(sql);
  if (sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error != nullptr ? error : sqlite3_errmsg(db_);
    sqlite3_free(error);
    throw RecordsError(fmt::format("records database {}: {}: {}", file_.string(), text, message));
  }
}

int64_t SqliteDatabase::LastInsertRowId() const { return sqlite3_last_insert_rowid(db_); }

void SqliteDatabase::Fail(const std::string& what) const {
  throw RecordsError(
      fmt::format("records database {}: {}: {}", file_.string(), what, sqlite3_errmsg(db_)));
}

SqliteStatement::SqliteStatement(SqliteDatabase& database, std::string_view sql)
    : database_(&database), sql_(sql) {
  if (sqlite3_prepare_v2(
          database.handle(), sql_.c_str(), static_cast<int>(sql_.size()), &statement_, nullptr) !=
      SQLITE_OK) {
    Fail("prepare");
  }
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(statement_); }

void SqliteStatement::Fail(const std::string& what) const {
  database_->Fail(fmt::format("{} '{}'", what, sql_));
}

SqliteStatement& SqliteStatement::Bind(int index, int64_t value) {
  if (sqlite3_bind_int64(statement_, index, value) != SQLITE_OK) Fail("bind");
  return *this;
}

SqliteStatement& SqliteStatement::Bind(int index, double value) {
  if (sqlite3_bind_double(statement_, index, value) != SQLITE_OK) Fail("bind");
  return *this;
}

SqliteStatement& SqliteStatement::Bind(int index, std::string_view value) {
  if (sqlite3_bind_text(
          statement_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT) !=
      SQLITE_OK) {
    Fail("bind");
  }
  return *this;
}

SqliteStatement& SqliteStatement::BindNull(int index) {
  if (sqlite3_bind_null(statement_, index) != SQLITE_OK) Fail("bind");
  return *this;
}

SqliteStatement& SqliteStatement::Bind(int index, const std::optional<int64_t>& value) {
  return value ? Bind(index, *value) : BindNull(index);
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  Fail("step");
}

void SqliteStatement::Run() {
  if (Step()) Fail("unexpected row from");
}

bool SqliteStatement::IsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

int64_t SqliteStatement::Int(int column) const { return sqlite3_column_int64(statement_, column); }

double SqliteStatement::Real(int column) const { return sqlite3_column_double(statement_, column); }

std::string SqliteStatement::Text(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  return text != nullptr ? std::string(reinterpret_cast<const char*>(text)) : std::string();
}

std::optional<int64_t> SqliteStatement::OptionalInt(int column) const {
  if (IsNull(column)) return std::nullopt;
  return Int(column);
}

SqliteTransaction::SqliteTransaction(SqliteDatabase& database) : database_(&database) {
  database_->Execute("BEGIN IMMEDIATE");
}

SqliteTransaction::~SqliteTransaction() {
  if (!done_) sqlite3_exec(database_->handle(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void SqliteTransaction::Commit() {
  database_->Execute("COMMIT");
  done_ = true;
}

}  // namespace adahrs::calib
