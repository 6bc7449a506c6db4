// The campaign journal, `<out_dir>/campaign-journal.json` (docs/campaign.md "Resuming"): which
// stages of a campaign have finished and which units took their constants with a verified
// read-back, so that a campaign killed at any point continues where it stopped. Each change
// rewrites the whole file atomically (common::WriteFileAtomically): a crash or power loss leaves
// the previous journal or the new one, never a part. A download is keyed by the unit's serial and
// the SHA-256 of its constants file: the same unit with changed constants is downloaded again.
// The journal is written after the fact: a campaign killed between a unit's commit and the
// journal's write downloads that unit again on resume (and the records show both downloads).
// A malformed journal is refused naming the file and the JSON path.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/campaign/station_download.h"

namespace adahrs::calib {

inline constexpr const char* kCampaignJournalFile = "campaign-journal.json";

class CampaignJournal {
 public:
  /// Reads `<out_dir>/campaign-journal.json` if there is one; an empty journal otherwise.
  explicit CampaignJournal(const std::filesystem::path& out_dir);

  bool Done(const std::string& stage) const;
  /// Records `stage` as finished and writes the journal.
  void MarkDone(const std::string& stage);
  /// The unit's download of the constants whose file has `constants_sha256`, if it verified.
  std::optional<UnitDownload> VerifiedDownload(const std::string& serial,
                                               const std::string& constants_sha256) const;
  /// Records a verified and committed download and writes the journal.
  void RecordDownload(const UnitDownload& download);

  const std::filesystem::path& file() const { return file_; }
  nlohmann::json ToJson() const;

 private:
  struct Stage {
    std::string name;
    std::string finished_utc;
  };
  struct Download {
    UnitDownload unit;
    std::string verified_utc;
  };
  void Write() const;

  std::filesystem::path file_;
  std::vector<Stage> stages_;
  std::vector<Download> downloads_;
};

}  // namespace adahrs::calib
