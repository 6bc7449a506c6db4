// adahrs rig: the virtual lab on pseudo-terminals until SIGINT/SIGTERM (docs/rig.md).
#include <pthread.h>
#include <signal.h>

#include <iostream>

#include <fmt/format.h>

#include "apps/commands.h"
#include "rig_sim/rig.h"

namespace adahrs::apps {

void RegisterRigCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "rig", "Serve the virtual rig (instruments and units) on pseudo-terminals until stopped");
  struct Options {
    std::string config_path;
    std::string manifest_path;
    std::string run_dir;
    double time_scale = 0.0;
    bool print_default = false;
    bool lockstep = false;
    bool packet_log = false;
  };
  auto options = std::make_shared<Options>();
  cmd->add_option("--config", options->config_path, "Rig configuration JSON (default: built in)");
  cmd->add_option("--manifest",
                  options->manifest_path,
                  "Where to write the manifest (role -> port) once every port is open");
  cmd->add_option("--time-scale",
                  options->time_scale,
                  "Simulated seconds per wall second (overrides the config)")
      ->check(CLI::Range(0.01, 100000.0));
  cmd->add_flag("--lockstep",
                options->lockstep,
                "The clock waits for every reading client; --time-scale is its top speed");
  cmd->add_flag("--packet-log",
                options->packet_log,
                "Log every unit packet's sample index in the run directory's packets/<role>.txt");
  cmd->add_option("--run-dir",
                  options->run_dir,
                  "Run directory for truth/ and ports/ (default: the manifest's directory)");
  cmd->add_flag("--print-default-config",
                options->print_default,
                "Print the built-in configuration and exit");
  cmd->callback([options] {
    if (options->print_default) {
      std::cout << rig_sim::DefaultRigConfig().dump(2) << "\n";
      return;
    }
    if (options->manifest_path.empty()) {
      throw CLI::RequiredError("--manifest");
    }
    rig_sim::RigConfig config =
        options->config_path.empty()
            ? rig_sim::RigConfig::FromJson(rig_sim::DefaultRigConfig(), "built-in rig config")
            : rig_sim::RigConfig::Load(options->config_path);
    if (options->time_scale > 0.0) config.time_scale = options->time_scale;
    if (options->lockstep) config.lockstep = true;
    if (options->packet_log) config.packet_log = true;
    const std::filesystem::path manifest = std::filesystem::absolute(options->manifest_path);
    const std::filesystem::path run_dir =
        options->run_dir.empty() ? manifest.parent_path() : std::filesystem::path(options->run_dir);

    // Block the stop signals before any thread starts, so they are delivered to sigwait here.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    const std::string claimed = rig_sim::ClaimManifestPath(manifest);
    if (!claimed.empty()) std::cout << "rig: " << claimed << "\n";
    rig_sim::Rig rig(config, run_dir);
    rig.Start(manifest);
    for (const auto& [role, path] : rig.ports()) {
      std::cout << fmt::format("{:<14} {}\n", role, path);
    }
    std::cout << fmt::format("rig running at {}{:g}x; manifest {}; stop with SIGINT or SIGTERM\n",
                             config.lockstep ? "lockstep, up to " : "",
                             config.time_scale,
                             manifest.string())
              << std::flush;
    int signal_number = 0;
    sigwait(&stop_signals, &signal_number);
    rig.Stop();
    std::cout << fmt::format(
        "rig stopped by signal {} at simulated t = {:.2f} s\n", signal_number, rig.host().now_s());
    for (const std::string& line : rig.host().Report()) std::cout << line << "\n";
  });
}

}  // namespace adahrs::apps
