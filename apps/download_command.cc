// adahrs download --station FILE --unit ROLE --constants FILE [--db FILE]: writes a unit's
// constants over its maintenance port, verifies the read-back bit for bit, commits and switches the
// unit to its calibrated mode (calib/download/, docs/download.md): a file of one stage of the
// staged process (`fit --stage`) sets the mode after that stage. With --db, the constants file
// is recorded as a version and the attempt (committed or refused) as a download of it.
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/constants/constants_file.h"
#include "calib/constants/provenance_check.h"
#include "calib/download/constants_download.h"
#include "calib/records/download_records.h"
#include "calib/records/records_sources.h"
#include "calib/records/records_store.h"
#include "hil/clock.h"
#include "hil/drivers/unit_link.h"
#include "hil/drivers/unit_mode.h"
#include "hil/station.h"

namespace adahrs::apps {
namespace {

struct DownloadOptions {
  std::string station;
  std::string unit;
  std::string constants;
  std::string db;
};

void Download(const DownloadOptions& options) {
  const hil::Station station = hil::Station::Load(options.station);
  const hil::UnitEntry* entry = nullptr;
  for (const hil::UnitEntry& unit : station.units) {
    if (unit.role == options.unit) entry = &unit;
  }
  if (entry == nullptr) {
    throw std::runtime_error(
        fmt::format("{}: the station has no unit with role '{}'", options.station, options.unit));
  }
  const calib::ConstantsFile file = calib::ReadConstantsFile(options.constants);
  for (const calib::RecordingCheck& c :
       calib::RequireUnchangedRecordings(file, options.constants)) {
    if (!c.current_sha256) std::cout << "provenance: recording " << c.Describe() << "\n";
  }
  std::optional<calib::RecordsStore> store;
  if (!options.db.empty()) store.emplace(options.db);
  // Recorded once the outcome is known: a refused file never becomes a constants version.
  const auto record_attempt = [&](const calib::DownloadRecord& attempt) {
    if (!store) return;
    if (!calib::RecordDownloadAttempt(
            *store, calib::ConstantsRecordFromFile(options.constants), attempt)) {
      std::cout << fmt::format(
          "records: nothing recorded in {}: the unit refused a file that is no constants "
          "version of {} yet\n",
          options.db,
          file.serial);
    }
  };
  const std::unique_ptr<hil::Clock> clock = hil::MakeClock(station.time_scale, station.clock_file);
  hil::UnitLink link(*entry, *clock);
  calib::DownloadRecord record{
      file.serial, 0, station.name, entry->role, false, false, std::nullopt, std::nullopt, ""};
  try {
    const calib::DownloadResult result = calib::DownloadConstants(link, file, options.constants);
    std::cout << fmt::format("{} ({} on {}): {} blocks written and read back equal\n",
                             file.serial,
                             entry->role,
                             entry->port.path,
                             result.blocks.blocks.size());
    for (const calib::ExportErrorBound& bound : result.blocks.error_bounds) {
      std::cout << fmt::format(
          "  fixed-point error bound {}: {:.3g}\n", bound.quantity, bound.bound);
    }
    std::cout << fmt::format("committed: constants version {} -> {}, crc 0x{:04X}; mode {}\n",
                             result.before.constants_version,
                             result.after.constants_version,
                             result.after.constants_crc,
                             hil::UnitModeName(file.kind, result.mode));
    record.verified = record.committed = true;
    record.unit_constants_version = result.after.constants_version;
    record.unit_constants_crc = result.after.constants_crc;
    record.detail = "ok";
    record_attempt(record);
  } catch (const calib::DownloadError& e) {
    record.verified = e.verified();
    record.detail = e.what();
    record_attempt(record);
    throw;
  }
}

}  // namespace

void RegisterDownloadCommand(CLI::App& app) {
  CLI::App* download = app.add_subcommand(
      "download", "Write a constants.json into a unit: read back, verify, commit, calibrated mode");
  auto options = std::make_shared<DownloadOptions>();
  download->add_option("--station", options->station, "Station file")->required();
  download->add_option("--unit", options->unit, "Unit role in the station, e.g. imu1")->required();
  download->add_option("--constants", options->constants, "constants.json of that unit")
      ->required();
  download->add_option("--db", options->db, "Records database to record the download in");
  download->callback([options] { Download(*options); });
}

}  // namespace adahrs::apps
