#include "apps/campaign_console.h"

#include <iostream>

#include <fmt/format.h>

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

}  // namespace adahrs::apps
