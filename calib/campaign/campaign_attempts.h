// Acceptance attempts of a campaign (docs/campaign.md "Retests"): the first acceptance run holds
// every unit of a bench; a unit whose outcome is FAIL is run again, alone with the other units
// that failed on its bench, up to the campaign file's retest.max_attempts, each attempt a whole
// run of the acceptance sequence in its own directory ("<first run>-attempt<N>") on a station
// file that names only those units. PASS and MARGINAL are not retested. Every attempt is judged,
// written (acceptance.json per unit) and recorded as an attempt (calib/records/yield_records.h);
// a unit's last attempt is its verdict.
// Left out: retesting a unit that passed (an operator's choice), a hold between attempts for the
// operator to re-seat a unit.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "calib/acceptance/acceptance_judge.h"
#include "calib/records/yield_records.h"
#include "hil/station.h"

namespace adahrs::calib {

/// The directory of `attempt` of the acceptance run whose first attempt is in `first_run`:
/// `first_run` itself for attempt 1, "<first_run>-attempt<N>" for a retest.
std::filesystem::path AttemptRunDir(const std::filesystem::path& first_run, int attempt);

/// The roles (from `role_of_serial`) of the units whose outcome in `judged` is FAIL; throws
/// std::runtime_error naming the serial if one has no role.
std::set<std::string> FailedRoles(const AcceptanceRun& judged,
                                  const std::map<std::string, std::string>& role_of_serial);

/// `station` with only the units whose role is in `roles`.
hil::Station StationWithRoles(const hil::Station& station, const std::set<std::string>& roles);

/// The acceptance.json of every unit of `judged` under `dir` (<dir>/<serial>/acceptance.json).
/// Files already there for every unit are kept as they are (a resumed campaign judges the same
/// complete recording again and keeps the files it recorded, so their checksums stay); otherwise
/// they are written (WriteAcceptanceFiles).
std::vector<std::filesystem::path> AcceptanceFilesOf(const AcceptanceRun& judged,
                                                     const Specification& spec,
                                                     const std::string& software_version,
                                                     const std::filesystem::path& dir);

/// The attempt records of `judged`'s units, one per file of `files` (AcceptanceFilesOf's order).
std::vector<AcceptanceAttemptRecord> AttemptRecords(
    const std::string& campaign_id,
    int attempt,
    const AcceptanceRun& judged,
    const std::vector<std::filesystem::path>& files,
    const std::map<std::string, std::string>& role_of_serial);

}  // namespace adahrs::calib
