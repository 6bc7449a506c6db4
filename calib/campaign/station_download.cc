#include "calib/campaign/station_download.h"

#include <memory>

#include "calib/constants/constants_file.h"
#include "calib/download/constants_download.h"
#include "calib/executor/executor.h"
#include "calib/records/records_sources.h"
#include "common/sha256.h"
#include "hil/clock.h"
#include "hil/drivers/unit_link.h"
#include "hil/drivers/unit_serial.h"

namespace adahrs::calib {

std::vector<UnitDownload> DownloadStation(const hil::Station& station,
                                          const std::filesystem::path& fit_dir,
                                          RecordsStore& records,
                                          const DownloadLedger& ledger,
                                          const std::atomic<bool>* stop) {
  const std::unique_ptr<hil::Clock> clock = hil::MakeClock(station.time_scale, station.clock_file);
  std::vector<UnitDownload> downloads;
  for (const hil::UnitEntry& entry : station.units) {
    if (stop != nullptr && *stop) {
      throw RunInterrupted("stopped before the download into " + entry.role);
    }
    hil::UnitLink link(entry, *clock);
    const hil::IdentifyInfo id = link.Identify();
    UnitDownload d;
    d.role = entry.role;
    d.serial = hil::UnitSerialText(entry.kind, id.serial_number);
    d.constants_file = fit_dir / (d.serial + ".json");
    if (!std::filesystem::exists(d.constants_file)) {
      throw DownloadError(entry.role + " (" + d.serial + " on " + entry.port.path +
                              "): no constants file " + d.constants_file.string(),
                          false);
    }
    d.constants_sha256 = common::FileSha256(d.constants_file);
    if (ledger.verified_before) {
      if (std::optional<UnitDownload> before =
              ledger.verified_before(d.serial, d.constants_sha256)) {
        downloads.push_back(*std::move(before));
        continue;
      }
    }
    const ConstantsFile file = ReadConstantsFile(d.constants_file);
    d.records_version = records.AddConstants(ConstantsRecordFromFile(d.constants_file));
    DownloadRecord record{d.serial,
                          d.records_version,
                          station.name,
                          entry.role,
                          false,
                          false,
                          std::nullopt,
                          std::nullopt,
                          ""};
    try {
      const DownloadResult result = DownloadConstants(link, file, d.constants_file.string());
      d.unit_constants_version = result.after.constants_version;
      d.unit_constants_crc = result.after.constants_crc;
      d.blocks = result.blocks.blocks.size();
      record.verified = record.committed = true;
      record.unit_constants_version = d.unit_constants_version;
      record.unit_constants_crc = d.unit_constants_crc;
      record.detail = "ok";
      records.AddDownload(record);
      if (ledger.verified) ledger.verified(d);
    } catch (const DownloadError& e) {
      record.verified = e.verified();
      record.detail = e.what();
      records.AddDownload(record);
      throw;
    }
    downloads.push_back(std::move(d));
  }
  return downloads;
}

}  // namespace adahrs::calib
