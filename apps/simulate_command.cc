// adahrs simulate static-thermal: a simulated static + thermal recording of a batch of units.
// adahrs simulate replay: a recording's stimulus re-simulated with unit model files.
#include <chrono>
#include <iostream>

#include <fmt/format.h>

#include "apps/commands.h"
#include "rig_sim/recording_replay.h"
#include "rig_sim/static_thermal_run.h"

namespace adahrs::apps {

namespace {

void RegisterReplay(CLI::App* sim) {
  CLI::App* cmd = sim->add_subcommand(
      "replay", "Re-simulate a recording's stimulus with unit model files (docs/diagnose.md)");
  struct Options {
    std::string run;
    std::vector<std::string> units;
    std::string out;
    bool same_noise = false;
    bool plain_csv = false;
    rig_sim::ReplayOptions replay;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("--run", o->run, "Run directory whose stimulus is replayed")->required();
  cmd->add_option("--unit",
                  o->units,
                  "Unit file of the truth schema (truth/<serial>.json, a diagnosis's model.json); "
                  "repeatable")
      ->required();
  cmd->add_option("--out", o->out, "New run directory to write")->required();
  cmd->add_option("--seed", o->replay.noise_seed, "Noise seed")->capture_default_str();
  cmd->add_flag("--same-noise",
                o->replay.noise_from_unit_file,
                "Each unit's noise as the rig drew it (the unit file's seed)");
  cmd->add_flag("--plain-csv", o->plain_csv, "Write imu.csv and ads.csv uncompressed");
  cmd->callback([o] {
    if (o->plain_csv) o->replay.storage = hil::RecordingStorage::kPlainCsv;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::filesystem::path> files(o->units.begin(), o->units.end());
    const rig_sim::ReplaySummary s = rig_sim::ReplayRecording(o->run, files, o->out, o->replay);
    std::string skipped;
    for (const std::string& x : s.skipped) skipped += (skipped.empty() ? "" : ", ") + x;
    std::cout << fmt::format(
        "replayed {} unit(s): {} IMU rows, {} ADS rows into {} in {:.1f} s{}\n",
        s.replayed.size(),
        s.imu_rows,
        s.ads_rows,
        o->out,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
        skipped.empty() ? "" : "; not replayed (no unit file): " + skipped);
  });
}

}  // namespace

void RegisterSimulateCommand(CLI::App& app) {
  CLI::App* sim = app.add_subcommand("simulate", "Simulated recordings without instruments");
  sim->require_subcommand(1);
  RegisterReplay(sim);
  CLI::App* cmd = sim->add_subcommand(
      "static-thermal",
      "Record a batch of simulated units, static in one orientation, through a chamber profile");
  struct Options {
    std::string out_dir = "runs/static-thermal";
    std::string profile = "truth";
    bool plain_csv = false;
    rig_sim::StaticThermalRunConfig config = rig_sim::StaticThermalRunConfig::Demo();
  };
  auto options = std::make_shared<Options>();
  cmd->add_option("--out", options->out_dir, "Run directory to write")->capture_default_str();
  cmd->add_option("--imu-units", options->config.imu_units, "IMU units in the batch (0-4)")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  cmd->add_option("--ads-units", options->config.ads_units, "ADS units in the batch (0-4)")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  cmd->add_option("--seed", options->config.seed, "Batch seed (units and noise)")
      ->capture_default_str();
  cmd->add_option("--model", options->profile, "Model profile: nominal or truth")
      ->check(CLI::IsMember({"nominal", "truth"}))
      ->capture_default_str();
  cmd->add_option("--orientation", options->config.orientation, "Fixture orientation code")
      ->check(CLI::IsMember({11, 12, 21, 22, 31, 32}))
      ->capture_default_str();
  cmd->add_option("--log-every", options->config.log_every, "Log every Nth packet")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--latitude-deg", options->config.latitude_deg, "Station latitude (gravity)")
      ->check(CLI::Range(-90.0, 90.0))
      ->capture_default_str();
  cmd->add_flag("--plain-csv", options->plain_csv, "Write imu.csv and ads.csv uncompressed");
  cmd->callback([options] {
    if (options->plain_csv) options->config.storage = hil::RecordingStorage::kPlainCsv;
    options->config.profile = sensor_sim::ModelProfileFromString(options->profile);
    const auto start = std::chrono::steady_clock::now();
    const auto summary =
        rig_sim::RunStaticThermal(options->config, options->out_dir, [&](int step, double t_s) {
          const auto& s = options->config.steps[static_cast<size_t>(step)];
          std::cout << fmt::format("step {} done: {:+.1f} degC reached and soaked, t = {:.0f} s\n",
                                   step,
                                   s.target_c,
                                   t_s);
        });
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << fmt::format(
        "recorded {:.1f} h of {} IMU + {} ADS units ({} IMU rows, {} ADS rows) into {} in {:.1f} s "
        "({:.0f}x real time)\n",
        summary.duration_s / 3600.0,
        options->config.imu_units,
        options->config.ads_units,
        summary.imu_rows,
        summary.ads_rows,
        options->out_dir,
        wall_s,
        summary.duration_s / wall_s);
  });
}

}  // namespace adahrs::apps
