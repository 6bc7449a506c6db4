// adahrs demo [--out DIR] [--time-scale K] [--quick]: the product's main job on the virtual lab
// (docs/demo.md). Starts the rig as a separate process (this binary's `rig` subcommand), writes
// the IMU-bench and ADS-bench station files for its ports, runs the calibration campaign
// (calib/campaign/campaign.h) with the rig's truth for the evaluation, prints a summary per unit,
// and always stops the rig. Thin: the rig process and the stations are rig_sim's, the chain is
// calib's; this file picks the files, prints, and handles SIGINT, SIGTERM and SIGHUP alike (exit
// 128 + the signal's number).
#include <signal.h>
#include "adahrs_build_paths.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/campaign_console.h"
#include "apps/commands.h"
#include "calib/acceptance/acceptance_file.h"
#include "calib/campaign/quick_sequences.h"
#include "proving/demo/demo_campaign.h"
#include "rig_sim/recording_replay.h"
#include "rig_sim/rig_bench_stations.h"
#include "rig_sim/rig_child_process.h"
#include "rig_sim/rig_config.h"

namespace adahrs::apps {
namespace {

std::atomic<bool> g_demo_stop{false};
std::atomic<int> g_demo_signal{SIGINT};
extern "C" void OnDemoStopSignal(int signal_number) {
  g_demo_signal = signal_number;
  g_demo_stop = true;
}

struct DemoOptions {
  std::string out = "runs/demo";
  double time_scale = 0.0;  // 0: kLockstepTimeScale, or kFreeRunningTimeScale with --free-running
  bool quick = false;
  std::string sequences = ADAHRS_SEQUENCE_DIR;
  std::string truth_variant = "standard";
  bool free_running = false;
};

// Default speeds: in lockstep the top speed (a slower machine makes the demo slower, not lossy);
// free-running the highest found loss-free through the whole demo on a 2-core machine.
constexpr double kLockstepTimeScale = 900.0;
constexpr double kFreeRunningTimeScale = 300.0;

// Exit status of a demo that completed but lost packets in a run.
constexpr int kExitPacketsLost = 3;

// Prints every run's rows and lost packets; returns the packets lost in all.
uint64_t PrintRuns(const std::vector<calib::RunSummary>& runs) {
  uint64_t lost = 0;
  for (const calib::RunSummary& r : runs) {
    std::cout << fmt::format(
        "run {}: {}, {} rows, {}\n",
        r.run_dir.filename().string(),
        r.status,
        r.rows,
        r.lost == 0 ? std::string("no packet lost") : fmt::format("{} PACKETS LOST", r.lost));
    lost += r.lost;
  }
  return lost;
}

void PrintSummary(const proving::DemoCampaignResult& result,
                  double wall_s,
                  sensor_sim::TruthVariant variant) {
  std::cout << fmt::format("\ndemo finished in {:.0f} s wall\n", wall_s);
  std::cout << fmt::format("truth: every modelled effect on, variant {}: {}\n",
                           sensor_sim::ToString(variant),
                           sensor_sim::Describe(variant));
  for (const calib::UnitOutcome& u : result.production.units) {
    PrintUnitOutcome(u);
    const auto evaluation = result.evaluation.find(u.serial);
    for (const proving::EvaluatedQuantity& q : evaluation == result.evaluation.end()
                                                   ? std::vector<proving::EvaluatedQuantity>{}
                                                   : evaluation->second) {
      std::cout << fmt::format("  evaluated worst {}: {:.4g} {} (spec {:g}) -> {}\n",
                               q.quantity,
                               q.worst,
                               q.unit,
                               q.tolerance,
                               q.verdict);
    }
    std::cout << "  report: " << u.report.string() << "\n";
  }
  for (const auto* evaluation : {&result.reference_evaluation, &result.ads_reference_evaluation}) {
    for (const proving::EvaluatedQuantity& q : *evaluation) {
      std::cout << fmt::format("reference strategy, {} worst {}: {:.4g} {} -> {}\n",
                               q.serial,
                               q.quantity,
                               q.worst,
                               q.unit,
                               q.verdict);
    }
  }
  std::cout << "diagnosis of the IMU and ADS calibration runs against the nominal model ("
            << (result.diagnosis_dir / "report.html").string() << "):\n";
  for (const diagnosis::UnitDiagnosis& u : result.diagnosis) {
    std::cout << fmt::format(
        "  {}: {} finding(s), {} unexplained\n", u.serial, u.findings.size(), u.unexplained.size());
  }
  for (const proving::DiagnosisTruthLine& l : result.diagnosis_truth) {
    std::cout << fmt::format("  {} {} {}: {}\n", l.serial, l.channel, l.effect, l.text);
  }
  for (const diagnosis::ReplayComparison& c : result.replay_checks) {
    std::cout << fmt::format(
        "held-out check: {} re-simulated, RMS of its acquisition means, recorded - replayed:\n",
        c.recording.filename().string());
    for (const diagnosis::UnitReplayFit& u : c.units) {
      for (const diagnosis::ChannelReplayFit& ch : u.channels) {
        std::cout << fmt::format(
            "  {} {:<3}: {:.3g} {} with the base model, {:.3g} with model.json (noise alone "
            "{:.2g})\n",
            u.serial,
            ch.channel,
            ch.rms_base,
            ch.unit,
            ch.rms_model,
            ch.rms_noise);
      }
    }
  }
  for (const std::string& s : result.production.not_run) std::cout << "not run: " << s << "\n";
  std::cout << "records: " << result.production.records_file.string()
            << " (adahrs units show SERIAL --db " << result.production.records_file.string()
            << ")\n";
}

int RunDemo(const DemoOptions& options) {
  struct sigaction action {};
  action.sa_handler = OnDemoStopSignal;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
  const auto start = std::chrono::steady_clock::now();
  const double time_scale = options.time_scale > 0.0 ? options.time_scale
                            : options.free_running   ? kFreeRunningTimeScale
                                                     : kLockstepTimeScale;
  const std::filesystem::path out = std::filesystem::absolute(options.out);
  if (std::filesystem::exists(out) && !std::filesystem::is_empty(out)) {
    throw std::runtime_error(out.string() + " is not empty: give a new --out directory");
  }
  const std::filesystem::path rig_dir = out / "rig";
  std::filesystem::create_directories(rig_dir);
  nlohmann::json rig_json = rig_sim::DefaultRigConfig();
  rig_json["units"]["truth_variant"] = options.truth_variant;
  const rig_sim::RigConfig rig_config =
      rig_sim::RigConfig::FromJson(rig_json, "built-in rig config");
  std::ofstream(rig_dir / "rig.json") << rig_json.dump(2) << "\n";
  std::cout << fmt::format("truth: every modelled effect on, variant {}: {}\n",
                           sensor_sim::ToString(rig_config.truth_variant),
                           sensor_sim::Describe(rig_config.truth_variant));

  std::cout << fmt::format("starting the virtual rig {} {:g}x in {}\n",
                           options.free_running ? "free-running at" : "in lockstep, at most",
                           time_scale,
                           rig_dir.string());
  rig_sim::RigChildProcess rig(
      {"/proc/self/exe", rig_dir, rig_dir / "rig.json", time_scale, 30.0, !options.free_running});
  const auto station_file = [&](rig_sim::RigBench bench, const char* name) {
    const std::filesystem::path path = out / name;
    rig_sim::WriteStationFile(
        rig_sim::BenchStation(bench, rig.manifest(), rig_config, path.string()), path);
    return path.string();
  };
  proving::DemoCampaignOptions demo;
  calib::CampaignOptions& campaign = demo.campaign;
  campaign.out_dir = out;
  campaign.imu_station_file = station_file(rig_sim::RigBench::kImu, "station-imu.json");
  campaign.ads_station_file = station_file(rig_sim::RigBench::kAds, "station-ads.json");
  const std::filesystem::path dir = options.sequences;
  campaign.sequences = {{(dir / "imu_thermal_sensor_calibration.json").string()},
                        (dir / "ads_calibration.json").string(),
                        (dir / "imu_acceptance.json").string(),
                        (dir / "ads_acceptance.json").string()};
  if (options.quick) {
    campaign.sequences = calib::WriteQuickSequences(campaign.sequences, out / "sequences");
  }
  demo.truth_dir = rig.truth_dir();
  campaign.software_version = ADAHRS_VERSION;
  demo.replay = [](const std::filesystem::path& run,
                   const std::vector<std::filesystem::path>& files,
                   const std::filesystem::path& to) { rig_sim::ReplayRecording(run, files, to); };
  // The rig is not needed after the acceptance runs: stopped then, it leaves both cores to the
  // analysis stages.
  campaign.stations_done = [&rig] { rig.Stop(); };
  ConsoleObserver observer;
  try {
    const proving::DemoCampaignResult result =
        proving::RunDemoCampaign(demo, observer, g_demo_stop);
    rig.Stop();
    PrintSummary(result,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 rig_config.truth_variant);
    if (const uint64_t lost = PrintRuns(result.production.runs); lost > 0) {
      std::cout << fmt::format("adahrs demo: {} packets lost: the runs are not complete\n", lost);
      return kExitPacketsLost;
    }
    return 0;
  } catch (const calib::RunInterrupted& e) {
    std::cerr << "adahrs demo: interrupted by signal " << g_demo_signal.load() << " (" << e.what()
              << "); the rig is stopped\n";
    return 128 + g_demo_signal.load();
  } catch (const std::exception& e) {
    if (const std::optional<std::string> exit = rig.ExitDescription()) {
      throw std::runtime_error(std::string(e.what()) + " (the rig " + *exit + ")");
    }
    throw;
  }
}

}  // namespace

void RegisterDemoCommand(CLI::App& app) {
  CLI::App* demo = app.add_subcommand(
      "demo",
      "The main job on the virtual lab: rig, calibration, fits, download, acceptance, "
      "evaluation, reports, records (docs/demo.md)");
  auto options = std::make_shared<DemoOptions>();
  demo->add_option("--out", options->out, "Demo directory (must be new or empty)")
      ->capture_default_str();
  demo->add_option("--time-scale",
                   options->time_scale,
                   "Rig speed, simulated s per wall s: the top speed in lockstep (default 900), "
                   "the speed with --free-running (default 300)")
      ->check(CLI::Range(1.0, 900.0));
  demo->add_flag("--free-running",
                 options->free_running,
                 "Run the rig on the wall clock (it may outrun a slow machine and lose packets) "
                 "instead of in lockstep with its readers");
  demo->add_flag(
      "--quick", options->quick, "Shorter sequences (docs/demo.md says what is trimmed)");
  demo->add_option("--sequences", options->sequences, "Directory of the reference sequences")
      ->capture_default_str();
  demo->add_option("--truth-variant",
                   options->truth_variant,
                   "The units' truth in model form: standard, play_hysteresis or slow_bias_wander "
                   "(docs/sensor-models.md)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](const std::string& name) {
            try {
              sensor_sim::TruthVariantFromString(name);
              return std::string();
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
          },
          "VARIANT"));
  demo->callback([options] {
    const int status = RunDemo(*options);
    if (status != 0) std::exit(status);
  });
}

}  // namespace adahrs::apps
