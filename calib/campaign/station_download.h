// The download stage of a calibration campaign: every unit of a station gets the constants file
// fitted for it (`<fit_dir>/<serial>.json`, the serial from the unit's own IDENTIFY,
// unit_serial.h) through DownloadConstants (constants_download.h: written, read back bit for bit,
// committed, calibrated mode), and each attempt is recorded in the production records (the
// constants file as a version, then the download, refused or committed).
// Errors: a unit with no constants file in `fit_dir` or a refused download throws DownloadError
// naming the unit, port, file and step, after the attempt is recorded; the units before it keep
// their new constants.
// A ledger (optional) skips a unit whose read-back already verified these same constants (their
// file's SHA-256) and hears of every verified download; a stop request is honoured between units
// (RunInterrupted), never inside a download.
// Left out: retrying a refused download.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calib/records/records_store.h"
#include "hil/station.h"

namespace adahrs::calib {

struct UnitDownload {
  std::string role;
  std::string serial;
  std::filesystem::path constants_file;
  std::string constants_sha256;         ///< of the constants file
  int64_t records_version = 0;          ///< version of the constants in the records
  uint16_t unit_constants_version = 0;  ///< the unit's commit count after the download
  uint16_t unit_constants_crc = 0;
  size_t blocks = 0;
};

/// What a campaign remembers of its downloads (campaign_journal.h); either may be empty.
struct DownloadLedger {
  /// The earlier verified download of these constants into this unit (serial, SHA-256), if any.
  std::function<std::optional<UnitDownload>(const std::string& serial, const std::string& sha256)>
      verified_before;
  /// Called after each verified and committed download.
  std::function<void(const UnitDownload&)> verified;
};

/// Downloads into every unit of `station`; returns one entry per unit, station order.
std::vector<UnitDownload> DownloadStation(const hil::Station& station,
                                          const std::filesystem::path& fit_dir,
                                          RecordsStore& records,
                                          const DownloadLedger& ledger = {},
                                          const std::atomic<bool>* stop = nullptr);

}  // namespace adahrs::calib
