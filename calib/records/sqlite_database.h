// A thin RAII layer over the SQLite C API (Debian libsqlite3): one connection per file, prepared
// statements with typed binding, transactions that roll back unless committed. WAL journal and
// foreign keys are switched on at open. Every failure throws RecordsError naming the database file,
// the SQL (or the operation) and SQLite's own message.
// Left out: connection pooling, busy-handler policy beyond a fixed timeout (5 s), blobs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace adahrs::calib {

class RecordsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SqliteDatabase;

/// One prepared statement. Parameters are 1-based as in SQLite; Step() returns true while a row is
/// available. Column getters are 0-based.
class SqliteStatement {
 public:
  SqliteStatement(SqliteDatabase& database, std::string_view sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  SqliteStatement& Bind(int index, int64_t value);
  SqliteStatement& Bind(int index, double value);
  SqliteStatement& Bind(int index, std::string_view value);
  SqliteStatement& BindNull(int index);
  SqliteStatement& Bind(int index, const std::optional<int64_t>& value);

  /// Advances; true when a row is available, false when done.
  bool Step();
  /// Runs a statement that returns no rows.
  void Run();

  bool IsNull(int column) const;
  int64_t Int(int column) const;
  double Real(int column) const;
  std::string Text(int column) const;
  std::optional<int64_t> OptionalInt(int column) const;

 private:
  [[noreturn]] void Fail(const std::string& what) const;

  SqliteDatabase* database_;
  std::string sql_;
  sqlite3_stmt* statement_ = nullptr;
};

class SqliteDatabase {
 public:
  /// Opens (creating if `create`; read-only if `read_only`, which never writes the file) the
  /// database file; throws RecordsError naming the file.
  SqliteDatabase(const std::filesystem::path& file, bool create, bool read_only = false);
  ~SqliteDatabase();
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  /// Runs one or more statements that return no rows.
  void Execute(std::string_view sql);
  int64_t LastInsertRowId() const;

  const std::filesystem::path& file() const { return file_; }
  sqlite3* handle() const { return db_; }
  /// "records database FILE: " + what + ": " + SQLite's message.
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  std::filesystem::path file_;
  sqlite3* db_ = nullptr;
};

/// BEGIN IMMEDIATE on construction; ROLLBACK on destruction unless Commit() was called.
class SqliteTransaction {
 public:
  explicit SqliteTransaction(SqliteDatabase& database);
  ~SqliteTransaction();
  SqliteTransaction(const SqliteTransaction&) = delete;
  SqliteTransaction& operator=(const SqliteTransaction&) = delete;
  void Commit();

 private:
  SqliteDatabase* database_;
  bool done_ = false;
};

}  // namespace adahrs::calib
