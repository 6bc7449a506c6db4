// What `adahrs campaign` and `adahrs demo` print while a campaign runs: each stage line with the
// wall time so far, and per bench a progress line at most every 5 s of wall time (time, step,
// action, ETA, packets lost). Thread-safe: both benches report at once. PrintUnitOutcome: a unit's
// constants, download and acceptance verdict as both commands print them at the end.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "calib/campaign/campaign.h"

namespace adahrs::apps {

class ConsoleObserver : public calib::CampaignObserver {
 public:
  void Stage(const std::string& text) override;
  calib::ProgressSink& Bench(const std::string& bench) override;

 private:
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<calib::ProgressSink>> sinks_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// A unit's constants version, download, acceptance outcome, worst margins and two-level rate
/// verdict, to standard output (the report path is the caller's: the demo prints its evaluation
/// before it).
void PrintUnitOutcome(const calib::UnitOutcome& u);

}  // namespace adahrs::apps
