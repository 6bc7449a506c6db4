// The production records (docs/records.md): what was run on which unit, which constants each unit
// was given (every version kept, never overwritten), whether they were downloaded and committed,
// every acceptance point's verdict and each unit's acceptance attempts in a campaign (first pass
// and retests, yield_records.h). Backed by one SQLite file (sqlite_database.h), schema and
// migrations in records_schema.h; every Add* runs in one transaction, so a failure leaves nothing
// half-recorded. Adding the same run recording (same run id and checksum), the same constants file
// (same serial and file checksum) or the same acceptance file again changes nothing and returns
// what is already there, so recording is safe to repeat.
// Left out: users and sign-offs, deletion of anything.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calib/records/sqlite_database.h"
#include "calib/records/yield_records.h"

namespace adahrs::calib {

struct RunUnitRecord {
  std::string serial;  ///< "IMU-0001"
  std::string kind;    ///< "imu" | "ads"
  std::string role;
  int slot = 0;
  std::string firmware;  ///< "M.m.p"
  std::optional<int64_t> constants_version;
  int mode = 0;
};

struct StepRecord {
  int index = 0;
  std::string kind;  ///< sequence step kind ("accel", "gyro", ...)
  int tag = 0;
  double rejected_s = 0.0;  ///< total length of the step's rejected intervals
};

struct RunRecord {
  std::string run_id;
  std::string run_dir;
  std::string sequence_name;
  std::string sequence_file;
  std::string station_name;
  std::string started_utc;
  std::string status;
  std::string recording_sha256;
  std::string meta_json;
  std::vector<RunUnitRecord> units;
  std::vector<StepRecord> steps;
};

struct ConstantsRecord {
  std::string serial;
  std::string kind;
  std::string strategy;
  std::string created_utc;
  std::string software_version;
  std::string file_sha256;      ///< of the constants.json bytes
  std::string json;             ///< the whole constants.json
  std::string provenance_json;  ///< its "provenance" object
};

struct DownloadRecord {
  std::string serial;
  int64_t constants_version = 0;  ///< records version (ConstantsVersion::version)
  std::string station_name;
  std::string role;
  bool verified = false;                          ///< every block read back bit for bit
  bool committed = false;                         ///< COMMIT acknowledged
  std::optional<int64_t> unit_constants_version;  ///< IDENTIFY after the commit
  std::optional<int64_t> unit_constants_crc;
  std::string detail;  ///< why it was refused, or "ok"
};

struct AcceptancePointRecord {
  std::string serial;
  std::string run_id;
  std::string quantity;   ///< "accel_x", "rate_z", "altitude", ...
  std::string condition;  ///< where it was judged: "orientation 11, 25 degC", "10000 ft, -40 degC"
  double error = 0.0;
  double tolerance = 0.0;
  std::string unit;  ///< of error and tolerance
  bool pass = false;
  std::string outcome;               ///< "PASS", "MARGINAL", "FAIL"
  std::string specification_sha256;  ///< of the specification file judged against ("": unknown)
};

/// One constants version of a unit as the history shows it.
struct ConstantsVersion {
  int64_t version = 0;
  std::string strategy;
  std::string created_utc;
  std::string file_sha256;
  std::string json;
  int downloads = 0;                              ///< attempts recorded
  bool committed = false;                         ///< at least one attempt committed
  std::optional<int64_t> unit_constants_version;  ///< of the latest committed download
  std::optional<int64_t> unit_constants_crc;
};

struct UnitRunEntry {
  std::string run_id;
  std::string run_dir;
  std::string sequence_name;
  std::string started_utc;
  std::string status;
  std::string recording_sha256;
  std::string role;
};

struct AcceptanceVerdict {
  std::string run_id;
  std::string source_sha256;
  int points = 0;
  int failed = 0;
  int marginal = 0;
  std::string specification_sha256;             ///< "" when recorded before it was kept
  std::vector<AcceptancePointRecord> failures;  ///< the failed points, for the history
};

struct UnitHistory {
  std::string serial;
  std::string kind;
  std::string first_seen_utc;
  std::vector<UnitRunEntry> runs;
  std::vector<ConstantsVersion> constants;
  std::vector<AcceptanceVerdict> acceptance;
};

class RecordsStore {
 public:
  /// Opens or creates `file` and brings its schema up to date.
  explicit RecordsStore(const std::filesystem::path& file);
  /// Opens an existing database for queries only: the file is never written, and one that does
  /// not hold this program's records schema is refused (RequireRecordsSchema).
  static RecordsStore OpenForReading(const std::filesystem::path& file);

  /// Records a run with its units and steps; returns false if that recording is already there.
  bool AddRun(const RunRecord& run);
  /// Records a constants file as the unit's next version; returns the version (the existing one
  /// if this exact file was recorded before).
  int64_t AddConstants(const ConstantsRecord& constants);
  /// Records a download attempt of a recorded constants version.
  void AddDownload(const DownloadRecord& download);
  /// Records the points of one acceptance file (`source_sha256` identifies it); returns false if
  /// that file was recorded before.
  bool AddAcceptance(const std::string& source_sha256,
                     const std::vector<AcceptancePointRecord>& points);

  /// Records one acceptance attempt of a unit in a campaign (yield_records.h); returns false if
  /// that attempt was recorded from the same acceptance file before; throws RecordsError if it was
  /// recorded from another.
  bool AddAcceptanceAttempt(const AcceptanceAttemptRecord& attempt);
  /// The yields of `campaign`, or of every campaign recorded when it is empty (by campaign id);
  /// throws RecordsError if a campaign named has no attempt.
  std::vector<CampaignYield> Yields(const std::string& campaign = "");

  /// The unit's version whose file checksum is `file_sha256`, if recorded.
  std::optional<int64_t> FindConstantsVersion(const std::string& serial,
                                              const std::string& file_sha256);
  /// Everything recorded about `serial`; throws RecordsError if the unit is unknown.
  UnitHistory History(const std::string& serial);

  const std::filesystem::path& file() const { return database_.file(); }

 private:
  struct ReadOnly {};
  RecordsStore(const std::filesystem::path& file, ReadOnly);
  void EnsureUnit(const std::string& serial, const std::string& kind);
  /// EnsureUnit with the kind its serial names ("IMU-…", "ADS-…").
  void EnsureUnit(const std::string& serial);

  SqliteDatabase database_;
};

}  // namespace adahrs::calib
