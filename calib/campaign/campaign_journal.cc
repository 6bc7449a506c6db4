#include "calib/campaign/campaign_journal.h"

#include <cstdint>

#include "common/atomic_file.h"
#include "common/param_reader.h"
#include "hil/utc_time.h"

namespace adahrs::calib {
namespace {

using common::ParamReader;

constexpr const char* kFormat = "adahrs-campaign-journal";
constexpr int kFormatVersion = 1;

nlohmann::json DownloadJson(const UnitDownload& d) {
  return {{"role", d.role},
          {"serial", d.serial},
          {"constants_file", d.constants_file.string()},
          {"constants_sha256", d.constants_sha256},
          {"records_version", d.records_version},
          {"unit_constants_version", d.unit_constants_version},
          {"unit_constants_crc", d.unit_constants_crc},
          {"blocks", d.blocks}};
}

UnitDownload DownloadFromJson(const ParamReader& r) {
  UnitDownload d;
  d.role = r.String("role");
  d.serial = r.String("serial");
  d.constants_file = r.String("constants_file");
  d.constants_sha256 = r.String("constants_sha256");
  d.records_version = r.Integer("records_version", 0, INT64_MAX);
  d.unit_constants_version = static_cast<uint16_t>(r.Integer("unit_constants_version", 0, 65535));
  d.unit_constants_crc = static_cast<uint16_t>(r.Integer("unit_constants_crc", 0, 65535));
  d.blocks = static_cast<size_t>(r.Integer("blocks", 0, 1 << 20));
  return d;
}

}  // namespace

CampaignJournal::CampaignJournal(const std::filesystem::path& out_dir)
    : file_(out_dir / kCampaignJournalFile) {
  if (!std::filesystem::exists(file_)) return;
  const nlohmann::json document = ParamReader::LoadFile(file_.string());
  const ParamReader r(document, file_.string());
  if (r.String("format") != kFormat || r.Integer("format_version", 1, 1000) != kFormatVersion) {
    r.Fail("$", std::string("not a ") + kFormat + " version " + std::to_string(kFormatVersion));
  }
  const size_t stages = r.ArrayLength("stages", 0, 1000);
  for (size_t i = 0; i < stages; ++i) {
    const ParamReader s = r.Element("stages", i, stages);
    stages_.push_back({s.String("stage"), s.String("finished_utc")});
    s.ExpectAllKeysUsed();
  }
  const size_t downloads = r.ArrayLength("downloads", 0, 100000);
  for (size_t i = 0; i < downloads; ++i) {
    const ParamReader d = r.Element("downloads", i, downloads);
    const ParamReader unit = d.Child("unit");
    downloads_.push_back({DownloadFromJson(unit), d.String("verified_utc")});
    unit.ExpectAllKeysUsed();
    d.ExpectAllKeysUsed();
  }
  r.ExpectAllKeysUsed();
}

bool CampaignJournal::Done(const std::string& stage) const {
  for (const Stage& s : stages_) {
    if (s.name == stage) return true;
  }
  return false;
}

void CampaignJournal::MarkDone(const std::string& stage) {
  if (Done(stage)) return;
  stages_.push_back({stage, hil::UtcNowIso8601()});
  Write();
}

std::optional<UnitDownload> CampaignJournal::VerifiedDownload(
    const std::string& serial, const std::string& constants_sha256) const {
  for (auto it = downloads_.rbegin(); it != downloads_.rend(); ++it) {
    if (it->unit.serial != serial) continue;
    // The unit's latest verified download decides: older constants do not count.
    if (it->unit.constants_sha256 == constants_sha256) return it->unit;
    return std::nullopt;
  }
  return std::nullopt;
}

void CampaignJournal::RecordDownload(const UnitDownload& download) {
  downloads_.push_back({download, hil::UtcNowIso8601()});
  Write();
}

nlohmann::json CampaignJournal::ToJson() const {
  nlohmann::json stages = nlohmann::json::array();
  for (const Stage& s : stages_)
    stages.push_back({{"stage", s.name}, {"finished_utc", s.finished_utc}});
  nlohmann::json downloads = nlohmann::json::array();
  for (const Download& d : downloads_) {
    downloads.push_back({{"unit", DownloadJson(d.unit)}, {"verified_utc", d.verified_utc}});
  }
  return {{"format", kFormat},
          {"format_version", kFormatVersion},
          {"stages", stages},
          {"downloads", downloads}};
}

void CampaignJournal::Write() const { common::WriteFileAtomically(file_, ToJson().dump(2) + "\n"); }

}  // namespace adahrs::calib
