// adahrs study --strategy A.json [--vs B.json] --units N --seed S [--profile truth|nominal|FILE]
//   [--threads T] [--shard i/n] --out DIR: a Monte Carlo study of calibration strategies
//   (docs/studies.md); prints progress (units done, units per minute, ETA) to stderr.
// adahrs study merge DIR... --out DIR: combines the shards of one study into the unsharded result.
#include <malloc.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "adahrs_build_paths.h"
#include "apps/commands.h"
#include "proving/studies/ads_study.h"
#include "proving/studies/imu_study.h"
#include "proving/studies/study_results.h"

namespace adahrs::apps {
namespace {

struct StudyArgs {
  std::string strategy;
  std::string vs;
  int units = 0;
  uint64_t seed = 0;
  std::string profile;
  int threads = 0;
  std::string shard = "1/1";
  std::string out;
  std::vector<std::string> merge_dirs;
  std::string merge_out;
};

// Units done, units per minute and ETA on one line (redrawn on a terminal, else every 5 %).
proving::StudyProgress ProgressPrinter() {
  const auto start = std::chrono::steady_clock::now();
  const bool tty = isatty(fileno(stderr)) != 0;
  return [start, tty](int done, int total) {
    const double minutes =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 60.0;
    const double per_minute = done / std::max(minutes, 1e-9);
    const double eta_min = (total - done) / std::max(per_minute, 1e-9);
    const std::string line = fmt::format("study: {}/{} units, {:.1f} units/min, ETA {:.0f} min{}",
                                         done,
                                         total,
                                         per_minute,
                                         eta_min,
                                         tty ? "" : "\n");
    if (tty) {
      std::cerr << "\r" << line << (done == total ? "\n" : "") << std::flush;
    } else if (done == total || (done * 20) / total != ((done - 1) * 20) / total) {
      std::cerr << line;
    }
  };
}

// Each unit allocates and frees blocks of tens of MB (a run's rows, the reference fit's design
// matrices). glibc hands blocks above its mmap threshold back to the kernel at once, so every
// unit faulted its pages in afresh: a third of a unit's CPU time was the kernel's. Keeping them in
// the heap for reuse removes that; the results are the same.
void KeepLargeBlocksForReuse() {
  mallopt(M_MMAP_THRESHOLD, 512 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

void RunStudy(const StudyArgs& a) {
  if (a.strategy.empty()) throw CLI::ValidationError("--strategy", "required (a study file)");
  if (a.out.empty()) throw CLI::ValidationError("--out", "required (the output directory)");
  if (a.units < 1) throw CLI::ValidationError("--units", "required, at least 1");
  std::vector<proving::StudyDefinition> strategies{
      proving::LoadStudyDefinition(a.strategy, ADAHRS_SEQUENCE_DIR)};
  if (!a.vs.empty()) strategies.push_back(proving::LoadStudyDefinition(a.vs, ADAHRS_SEQUENCE_DIR));
  if (strategies.size() == 2 && strategies[0].name == strategies[1].name) {
    throw CLI::ValidationError(
        "--vs", "the two study files have the same name \"" + strategies[0].name + "\"");
  }
  if (strategies.size() == 2 && strategies[0].unit_kind != strategies[1].unit_kind) {
    throw CLI::ValidationError("--vs",
                               strategies[1].file + ": $.unit_kind differs from " +
                                   strategies[0].file + " (a paired study draws one kind of unit)");
  }
  proving::StudySettings settings;
  settings.units = a.units;
  settings.seed = a.seed;
  settings.shard = proving::StudyShard::Parse(a.shard, "--shard");
  if (!a.profile.empty()) {
    settings.population = proving::ParsePopulation(
        a.profile, std::filesystem::current_path(), "command line", "--profile");
  } else if (strategies[0].population) {
    settings.population = *strategies[0].population;
  }
  for (const auto& d : strategies) {
    const proving::StudyPopulation population = d.population.value_or(proving::StudyPopulation{});
    if (a.profile.empty() && !(population == settings.population)) {
      throw CLI::ValidationError("--vs",
                                 d.file + ": $.population differs from " + strategies[0].file +
                                     " (a paired study draws one population; or give --profile)");
    }
  }
  KeepLargeBlocksForReuse();
  const bool ads = strategies[0].unit_kind == calib::UnitKind::kAds;
  const auto results =
      ads ? proving::RunAdsStudy(strategies, settings, a.threads, ProgressPrinter())
          : proving::RunImuStudy(strategies, settings, a.threads, ProgressPrinter());
  proving::WriteStudyOutputs(a.out, proving::MakeStudyMeta(strategies, settings), results);
  std::cout << fmt::format("{} units, shard {}: {}/results.csv, summary.json, report.html\n",
                           results.size(),
                           settings.shard.Label(),
                           a.out);
}

}  // namespace

void RegisterStudyCommand(CLI::App& app) {
  CLI::App* study =
      app.add_subcommand("study", "Monte Carlo yield of calibration strategies (docs/studies.md)");
  study->require_subcommand(0, 1);
  auto a = std::make_shared<StudyArgs>();
  study->add_option("--strategy", a->strategy, "Study file of the strategy (docs/studies.md)");
  study->add_option("--vs", a->vs, "Study file of a second strategy, compared unit by unit");
  study->add_option("--units", a->units, "Number of units drawn");
  study->add_option("--seed", a->seed, "Study seed: the units and their noise");
  study->add_option("--profile", a->profile, "Population: truth, nominal or a population file");
  study->add_option("--threads", a->threads, "Worker threads (default: all cores)");
  study->add_option("--shard", a->shard, "Run only shard i of n (i/n)");
  study->add_option("--out", a->out, "Output directory");
  CLI::App* merge = study->add_subcommand("merge", "Combine the shards of one study");
  merge->add_option("DIR", a->merge_dirs, "Shard output directories")->required();
  merge->add_option("--out", a->merge_out, "Output directory")->required();
  merge->callback([a] {
    std::vector<std::filesystem::path> dirs(a->merge_dirs.begin(), a->merge_dirs.end());
    proving::MergeStudies(dirs, a->merge_out);
    std::cout << fmt::format("{} shards merged into {}\n", dirs.size(), a->merge_out);
  });
  study->callback([a, merge] {
    if (merge->parsed()) return;
    RunStudy(*a);
  });
}

}  // namespace adahrs::apps
