// Acceptance attempts and yield (docs/records.md "Attempts and yield"): every acceptance of a unit
// in a campaign is one attempt, numbered from 1 (the first pass) in the order the campaign ran
// them (2.. are retests, calib/campaign/campaign.h). A unit passes an attempt when its acceptance
// outcome is PASS or MARGINAL. Over the units a campaign judged (a unit refused by its serial was
// never tested and is not counted):
//   first-pass yield = units whose attempt 1 passed / units judged;
//   final yield      = units whose last attempt passed / units judged (retests counted).
// Attempts are evidence: the table refuses UPDATE and DELETE.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

/// One acceptance attempt of a unit in a campaign.
struct AcceptanceAttemptRecord {
  std::string campaign;  ///< the campaign's id (calib/campaign/campaign_journal.h)
  std::string serial;
  std::string role;
  int attempt = 1;            ///< 1: the first pass; 2 and on: retests
  std::string run_id;         ///< of the acceptance run
  std::string source_sha256;  ///< of the unit's acceptance.json
  std::string outcome;        ///< "PASS", "MARGINAL" or "FAIL"
};

/// One unit's attempts in a campaign.
struct UnitAttempts {
  std::string serial;
  std::string role;
  std::vector<std::string> outcomes;  ///< per attempt, in order

  bool PassedFirst() const;
  bool PassedLast() const;
};

/// A campaign's yields, counted from its attempts.
struct CampaignYield {
  std::string campaign;
  std::vector<UnitAttempts> units;  ///< by serial

  int judged() const { return static_cast<int>(units.size()); }
  int first_pass() const;  ///< units whose first attempt passed
  int final_pass() const;  ///< units whose last attempt passed
  int retested() const;    ///< units with more than one attempt
  int attempts() const;
  nlohmann::json ToJson() const;
  /// "first-pass yield 3 of 4 (75.0 %) ...; final yield 4 of 4 (100.0 %) ...": says what each is.
  std::string Text() const;
};

/// True for "PASS" and "MARGINAL".
bool AttemptPassed(const std::string& outcome);

}  // namespace adahrs::calib
