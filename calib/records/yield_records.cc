#include "calib/records/yield_records.h"

#include <fmt/format.h>

#include "calib/records/records_store.h"
#include "calib/records/sqlite_database.h"
#include "hil/utc_time.h"

namespace adahrs::calib {
namespace {

std::string Percent(int part, int whole) {
  return whole == 0 ? std::string("n/a")
                    : fmt::format("{:.1f} %", 100.0 * static_cast<double>(part) / whole);
}

}  // namespace

bool AttemptPassed(const std::string& outcome) {
  return outcome == "PASS" || outcome == "MARGINAL";
}

bool UnitAttempts::PassedFirst() const {
  return !outcomes.empty() && AttemptPassed(outcomes.front());
}

bool UnitAttempts::PassedLast() const {
  return !outcomes.empty() && AttemptPassed(outcomes.back());
}

int CampaignYield::first_pass() const {
  int n = 0;
  for (const UnitAttempts& u : units) n += u.PassedFirst() ? 1 : 0;
  return n;
}

int CampaignYield::final_pass() const {
  int n = 0;
  for (const UnitAttempts& u : units) n += u.PassedLast() ? 1 : 0;
  return n;
}

int CampaignYield::retested() const {
  int n = 0;
  for (const UnitAttempts& u : units) n += u.outcomes.size() > 1 ? 1 : 0;
  return n;
}

int CampaignYield::attempts() const {
  int n = 0;
  for (const UnitAttempts& u : units) n += static_cast<int>(u.outcomes.size());
  return n;
}

nlohmann::json CampaignYield::ToJson() const {
  nlohmann::json per_unit = nlohmann::json::array();
  for (const UnitAttempts& u : units) {
    per_unit.push_back({{"serial", u.serial}, {"role", u.role}, {"outcomes", u.outcomes}});
  }
  return {{"campaign", campaign},
          {"units_judged", judged()},
          {"first_pass", first_pass()},
          {"final_pass", final_pass()},
          {"retested", retested()},
          {"attempts", attempts()},
          {"units", per_unit}};
}

std::string CampaignYield::Text() const {
  return fmt::format(
      "campaign {}: first-pass yield {} of {} ({}; a unit counts if its first acceptance "
      "attempt passed); final yield {} of {} ({}; a unit counts if its last attempt passed, "
      "retests included); {} unit(s) retested, {} attempts",
      campaign,
      first_pass(),
      judged(),
      Percent(first_pass(), judged()),
      final_pass(),
      judged(),
      Percent(final_pass(), judged()),
      retested(),
      attempts());
}

bool RecordsStore::AddAcceptanceAttempt(const AcceptanceAttemptRecord& a) {
  if (a.attempt < 1 || !(AttemptPassed(a.outcome) || a.outcome == "FAIL")) {
    throw RecordsError(fmt::format(
        "records database {}: acceptance attempt {} of {} in campaign {} with outcome '{}': "
        "attempts count from 1, outcomes are PASS, MARGINAL or FAIL",
        database_.file().string(),
        a.attempt,
        a.serial,
        a.campaign,
        a.outcome));
  }
  SqliteTransaction transaction(database_);
  SqliteStatement existing(database_,
                           "SELECT source_sha256 FROM acceptance_attempts WHERE campaign = ? AND "
                           "serial = ? AND attempt = ?");
  existing.Bind(1, a.campaign).Bind(2, a.serial).Bind(3, int64_t{a.attempt});
  if (existing.Step()) {
    if (existing.Text(0) == a.source_sha256) return false;
    throw RecordsError(fmt::format(
        "records database {}: campaign {} already has attempt {} of {} from another acceptance "
        "file ({}, not {})",
        database_.file().string(),
        a.campaign,
        a.attempt,
        a.serial,
        existing.Text(0),
        a.source_sha256));
  }
  EnsureUnit(a.serial);
  SqliteStatement(database_,
                  "INSERT INTO acceptance_attempts (campaign, serial, role, attempt, run_id, "
                  "source_sha256, outcome, recorded_utc) VALUES (?, ?, ?, ?, ?, ?, ?, ?)")
      .Bind(1, a.campaign)
      .Bind(2, a.serial)
      .Bind(3, a.role)
      .Bind(4, int64_t{a.attempt})
      .Bind(5, a.run_id)
      .Bind(6, a.source_sha256)
      .Bind(7, a.outcome)
      .Bind(8, hil::UtcNowIso8601())
      .Run();
  transaction.Commit();
  return true;
}

std::vector<CampaignYield> RecordsStore::Yields(const std::string& campaign) {
  SqliteStatement rows(database_,
                       "SELECT campaign, serial, role, outcome FROM acceptance_attempts WHERE "
                       "? = '' OR campaign = ? ORDER BY campaign, serial, attempt");
  rows.Bind(1, campaign).Bind(2, campaign);
  std::vector<CampaignYield> yields;
  while (rows.Step()) {
    if (yields.empty() || yields.back().campaign != rows.Text(0)) {
      yields.push_back({rows.Text(0), {}});
    }
    std::vector<UnitAttempts>& units = yields.back().units;
    if (units.empty() || units.back().serial != rows.Text(1)) {
      units.push_back({rows.Text(1), rows.Text(2), {}});
    }
    units.back().outcomes.push_back(rows.Text(3));
  }
  if (!campaign.empty() && yields.empty()) {
    throw RecordsError(fmt::format("records database {}: no acceptance attempt of campaign {}",
                                   database_.file().string(),
                                   campaign));
  }
  return yields;
}

}  // namespace adahrs::calib
