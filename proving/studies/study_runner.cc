#include "proving/studies/study_runner.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

#include "common/random.h"

namespace adahrs::proving {

StudyUnitResult NewStudyUnit(const StudySettings& settings, int index) {
  StudyUnitResult r;
  r.index = index;
  char serial[16];
  std::snprintf(serial, sizeof serial, "SIM-%06d", index + 1);
  r.serial = serial;
  r.draw_seed = common::Rng::Derive(settings.seed, 2 * static_cast<uint64_t>(index));
  r.noise_seed = common::Rng::Derive(settings.seed, 2 * static_cast<uint64_t>(index) + 1);
  return r;
}

std::vector<StudyUnitResult> RunStudyUnits(const StudySettings& settings,
                                           int threads,
                                           const StudyProgress& progress,
                                           const StudyUnitRunner& run) {
  std::vector<int> indices;
  for (int k = 0; k < settings.units; ++k) {
    if (settings.shard.Holds(k)) indices.push_back(k);
  }
  std::vector<StudyUnitResult> results(indices.size());
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min<int>(threads, std::max<int>(1, static_cast<int>(indices.size())));
  std::atomic<size_t> next{0};
  std::mutex mutex;
  int done = 0;
  std::exception_ptr error;
  auto work = [&] {
    for (size_t i = next++; i < indices.size(); i = next++) {
      try {
        results[i] = run(indices[i]);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
        next = indices.size();
        return;
      }
      const std::lock_guard lock(mutex);
      ++done;
      if (progress) progress(done, static_cast<int>(indices.size()));
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return results;
}

}  // namespace adahrs::proving
