// adahrs records add-run DIR | add-constants FILE... | yield [--campaign ID] [--json] and adahrs
// units show SERIAL: the production records database (calib/records/, docs/records.md). Recording
// is explicit and repeatable: adding the same run recording or constants file twice changes
// nothing.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/records/records_sources.h"
#include "calib/records/records_store.h"
#include "calib/records/unit_history_text.h"

namespace adahrs::apps {

inline constexpr const char* kDefaultRecordsDb = "records.sqlite";

void RegisterRecordsCommand(CLI::App& app) {
  CLI::App* records = app.add_subcommand("records", "Production records database (SQLite)");
  records->require_subcommand(1);
  auto db = std::make_shared<std::string>(kDefaultRecordsDb);

  CLI::App* add_run = records->add_subcommand("add-run", "Record a run directory (meta.json v2)");
  auto run_dir = std::make_shared<std::string>();
  add_run->add_option("DIR", *run_dir, "Run directory")->required();
  add_run->add_option("--db", *db, "Records database file")->capture_default_str();
  auto accept = std::make_shared<bool>(false);
  add_run->add_flag("--accept-sample-time-defects",
                    *accept,
                    "Record the run although rows' sample times left the bound of their line's "
                    "buffering (docs/recording-format.md \"Sample time\")");
  add_run->callback([run_dir, db, accept] {
    calib::RunRecordOptions options;
    options.accept_sample_time_defects = *accept;
    const calib::RunRecord run = calib::RunRecordFromDirectory(*run_dir, options);
    calib::RecordsStore store(*db);
    const bool added = store.AddRun(run);
    std::cout << fmt::format("run {} ({} units, {} steps, recording sha256 {}): {}\n",
                             run.run_id,
                             run.units.size(),
                             run.steps.size(),
                             run.recording_sha256,
                             added ? "recorded" : "already recorded");
  });

  CLI::App* add_constants =
      records->add_subcommand("add-constants", "Record constants.json files as new versions");
  auto files = std::make_shared<std::vector<std::string>>();
  add_constants->add_option("FILE", *files, "constants.json files")->required();
  add_constants->add_option("--db", *db, "Records database file")->capture_default_str();
  add_constants->callback([files, db] {
    calib::RecordsStore store(*db);
    for (const std::string& file : *files) {
      const calib::ConstantsRecord record = calib::ConstantsRecordFromFile(file);
      std::cout << fmt::format(
          "{}: {} constants version {}\n", file, record.serial, store.AddConstants(record));
    }
  });

  CLI::App* yield = records->add_subcommand(
      "yield", "First-pass and final acceptance yield per campaign (docs/records.md)");
  auto campaign = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  yield->add_option("--campaign", *campaign, "Campaign id (campaign-journal.json); default: all");
  yield->add_flag("--json", *json, "One JSON array of the campaigns' yields");
  yield->add_option("--db", *db, "Records database file")->capture_default_str();
  yield->callback([campaign, json, db] {
    if (!std::filesystem::exists(*db)) {
      throw calib::RecordsError(fmt::format("records database {}: no such file", *db));
    }
    calib::RecordsStore store = calib::RecordsStore::OpenForReading(*db);
    const std::vector<calib::CampaignYield> yields = store.Yields(*campaign);
    if (*json) {
      nlohmann::json all = nlohmann::json::array();
      for (const calib::CampaignYield& y : yields) all.push_back(y.ToJson());
      std::cout << all.dump(2) << "\n";
      return;
    }
    if (yields.empty())
      std::cout << "no campaign acceptance attempt is recorded in " << *db << "\n";
    for (const calib::CampaignYield& y : yields) std::cout << y.Text() << "\n";
  });

  CLI::App* units = app.add_subcommand("units", "Units in the production records");
  units->require_subcommand(1);
  CLI::App* show = units->add_subcommand("show", "Print a unit's history");
  auto serial = std::make_shared<std::string>();
  show->add_option("SERIAL", *serial, "Unit serial, e.g. IMU-0001")->required();
  show->add_option("--db", *db, "Records database file")->capture_default_str();
  show->callback([serial, db] {
    if (!std::filesystem::exists(*db)) {
      throw calib::RecordsError(fmt::format("records database {}: no such file", *db));
    }
    calib::RecordsStore store = calib::RecordsStore::OpenForReading(*db);
    std::cout << calib::FormatUnitHistory(store.History(*serial));
  });
}

}  // namespace adahrs::apps
