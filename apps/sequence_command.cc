// adahrs sequence check FILE [--station STATION]: validates a calibration sequence against the
// limits of the station's instruments (calib/sequence/station_limits.h; without --station, the
// reference hardware's defaults of calib/sequence/sequence_limits.h) and prints its expanded plan
// with a duration estimate (on the station's declared chamber rates and operator when given), or
// every problem found (exit status 1).
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "apps/commands.h"
#include "calib/sequence/execution_plan.h"
#include "calib/sequence/station_limits.h"
#include "calib/sequence/validation.h"

namespace adahrs::apps {
namespace {

std::string Hms(double s) {
  const long total = std::lround(s);
  return fmt::format("{}:{:02}:{:02}", total / 3600, (total / 60) % 60, total % 60);
}

void PrintPlan(const calib::Sequence& sequence, const calib::ExecutionPlan& plan) {
  std::cout << fmt::format("{} ({} sequence, {} steps): valid\n",
                           sequence.name,
                           calib::UnitKindName(sequence.unit_kind),
                           sequence.steps.size());
  std::cout << fmt::format("{:>9}  {:>4}  {:>3}  {}\n", "start", "step", "tag", "action");
  double t_s = 0.0;
  for (const calib::PlannedAction& a : plan.actions) {
    std::cout << fmt::format(
        "{:>9}  {:>4}  {:>3}  {}\n", Hms(t_s), a.step, a.tag, calib::Describe(a.action));
    t_s += a.estimate_s;
  }
  std::cout << fmt::format("{} actions, estimated duration {} ({:.0f} s)\n",
                           plan.actions.size(),
                           Hms(plan.duration_estimate_s),
                           plan.duration_estimate_s);
}

}  // namespace

void RegisterSequenceCommand(CLI::App& app) {
  CLI::App* sequence = app.add_subcommand("sequence", "Calibration sequences");
  sequence->require_subcommand(1);
  CLI::App* check = sequence->add_subcommand(
      "check", "Validate a sequence file; print its expanded plan or every problem");
  auto file = std::make_shared<std::string>();
  auto station_file = std::make_shared<std::string>();
  check->add_option("FILE", *file, "Sequence JSON file")->required();
  check->add_option("--station",
                    *station_file,
                    "Station file whose instrument limits the sequence must keep (default: the "
                    "reference hardware's)");
  check->callback([file, station_file] {
    if (station_file->empty()) {
      const calib::SequenceLimits limits;
      const calib::Sequence sequence = calib::LoadValidSequence(*file, limits);
      PrintPlan(sequence, calib::ExpandSequence(sequence, limits));
      return;
    }
    const hil::Station station = hil::Station::Load(*station_file);
    const calib::SequenceLimits limits = calib::LimitsForStation(station);
    const calib::Sequence sequence = calib::LoadValidSequence(*file, limits);
    PrintPlan(sequence,
              calib::ExpandSequence(
                  sequence, limits, calib::TimingForStation(station, sequence.unit_kind)));
  });
}

}  // namespace adahrs::apps
