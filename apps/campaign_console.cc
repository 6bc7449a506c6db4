#include "apps/campaign_console.h"

#include <iostream>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"

namespace adahrs::apps {
namespace {

// Wall seconds between two progress lines of one bench.
constexpr double kProgressLineIntervalS = 5.0;

class BenchSink : public calib::ProgressSink {
 public:
  BenchSink(std::string name, std::mutex& mutex) : name_(std::move(name)), mutex_(mutex) {}
  void Report(const calib::ProgressReport& r) override {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::duration<double>(kProgressLineIntervalS)) return;
    last_ = now;
    uint64_t lost = 0;
    for (const calib::UnitProgress& u : r.units) lost += u.lost;
    std::lock_guard lock(mutex_);
    std::cout << fmt::format("  [{}] t={:.0f} s step {}/{} {} | {} | ETA {:.0f} s | lost {}\n",
                             name_,
                             r.t_s,
                             r.step + 1,
                             r.step_count,
                             r.step_kind,
                             r.action_text,
                             r.eta_s,
                             lost)
              << std::flush;
  }
  void Note(const std::string& text) override {
    std::lock_guard lock(mutex_);
    std::cout << fmt::format("  [{}] note: {}\n", name_, text) << std::flush;
  }

 private:
  std::string name_;
  std::mutex& mutex_;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace

void ConsoleObserver::Stage(const std::string& text) {
  std::lock_guard lock(mutex_);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::cout << fmt::format("[{:4.0f} s] {}\n", wall_s, text) << std::flush;
}

calib::ProgressSink& ConsoleObserver::Bench(const std::string& bench) {
  std::lock_guard lock(mutex_);
  auto& sink = sinks_[bench];
  if (!sink) sink = std::make_unique<BenchSink>(bench, mutex_);
  return *sink;
}

void PrintUnitOutcome(const calib::UnitOutcome& u) {
  std::cout << fmt::format(
      "{} {}: constants version {} (records v{}, {} strategy, {} blocks verified)\n",
      u.role,
      u.serial,
      u.download.unit_constants_version,
      u.download.records_version,
      u.strategy,
      u.download.blocks);
  if (!u.acceptance) {
    std::cout << "  acceptance: the unit is not in the acceptance run\n";
    return;
  }
  std::cout << fmt::format("  acceptance: {} ({} of {} points fail, {} marginal)\n",
                           calib::OutcomeText(u.acceptance->outcome()),
                           u.acceptance->failed(),
                           u.acceptance->points.size(),
                           u.acceptance->marginal());
  for (const calib::WorstMargin& w : u.acceptance->WorstMargins()) {
    std::cout << fmt::format("    worst {} margin {:+.4g} {} at step {}: {}\n",
                             w.quantity,
                             w.margin,
                             w.unit,
                             w.step,
                             w.point);
  }
  if (const std::string line = calib::RateVerdictLine(*u.acceptance); !line.empty())
    std::cout << "    " << line;
}

}  // namespace adahrs::apps
