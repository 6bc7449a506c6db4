// adahrs campaign --campaign FILE [--station-imu FILE] [--station-ads FILE] --out DIR [--quick]
// adahrs campaign --resume DIR
// The production entry point (docs/campaign.md): runs the campaign file's stages
// (calib/campaign/campaign.h) on the stations the station files name, no simulator anywhere.
// The inputs as resolved (absolute paths, the --quick sequences) go to DIR/campaign.json, from
// which --resume continues. Prints a summary per unit. SIGINT, SIGTERM and SIGHUP stop the
// benches safely (the executor's safe stop) or stop between stages, and exit 128 + the signal.
// Exit status: 0 every unit accepted (PASS or MARGINAL); 4 complete, but a unit failed acceptance
// or was refused by its serial; 3 complete, but a run lost packets; 1 an error; 128 + N stopped by
// signal N (resumable).
#include <signal.h>
#include "adahrs_build_paths.h"

#include <atomic>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/campaign_console.h"
#include "apps/commands.h"
#include "calib/acceptance/acceptance_file.h"
#include "calib/campaign/campaign_file.h"
#include "calib/campaign/quick_sequences.h"
#include "common/atomic_file.h"
#include "common/param_reader.h"

namespace adahrs::apps {
namespace {

std::atomic<bool> g_campaign_stop{false};
std::atomic<int> g_campaign_signal{SIGINT};
extern "C" void OnCampaignStopSignal(int signal_number) {
  g_campaign_signal = signal_number;
  g_campaign_stop = true;
}

constexpr int kExitPacketsLost = 3;
constexpr int kExitUnitsNotAccepted = 4;
constexpr const char* kInputsFile = "campaign.json";

struct CampaignCommandOptions {
  std::string campaign_file;
  std::string station_imu;
  std::string station_ads;
  std::string out;
  std::string resume;
  bool quick = false;
};

// What a campaign was started with, as DIR/campaign.json keeps it for --resume.
struct CampaignInputs {
  calib::CampaignFile campaign;
  std::string station_imu, station_ads;  // absolute; empty: no such bench
};

std::string AbsoluteOrEmpty(const std::string& file) {
  return file.empty() ? file : std::filesystem::absolute(file).lexically_normal().string();
}

CampaignInputs NewCampaign(const CampaignCommandOptions& o, const std::filesystem::path& out) {
  if (o.campaign_file.empty()) throw CLI::RequiredError("--campaign");
  if (o.out.empty()) throw CLI::RequiredError("--out");
  if (o.station_imu.empty() && o.station_ads.empty()) {
    throw CLI::ValidationError("--station-imu/--station-ads", "give at least one station file");
  }
  if (std::filesystem::exists(out) && !std::filesystem::is_empty(out)) {
    throw std::runtime_error(out.string() +
                             " is not empty: give a new --out directory, or continue the "
                             "campaign in it with adahrs campaign --resume " +
                             out.string());
  }
  CampaignInputs in{calib::CampaignFile::Load(o.campaign_file),
                    AbsoluteOrEmpty(o.station_imu),
                    AbsoluteOrEmpty(o.station_ads)};
  std::filesystem::create_directories(out);
  if (o.quick) {
    in.campaign.sequences = calib::WriteQuickSequences(in.campaign.sequences, out / "sequences");
  }
  const nlohmann::json saved = {{"campaign", in.campaign.ToJson()},
                                {"station_imu", in.station_imu},
                                {"station_ads", in.station_ads}};
  common::WriteFileAtomically(out / kInputsFile, saved.dump(2) + "\n");
  return in;
}

CampaignInputs ResumedCampaign(const std::filesystem::path& out) {
  const std::filesystem::path file = out / kInputsFile;
  if (!std::filesystem::exists(file)) {
    throw std::runtime_error(out.string() + " holds no campaign (no " + kInputsFile + ")");
  }
  const nlohmann::json saved = common::ParamReader::LoadFile(file.string());
  const common::ParamReader r(saved, file.string());
  r.Child("campaign");  // an object, or refused naming the file and $.campaign
  CampaignInputs in{calib::CampaignFile::FromJson(saved.at("campaign"), file.string(), out),
                    r.String("station_imu"),
                    r.String("station_ads")};
  r.ExpectAllKeysUsed();
  return in;
}

void PrintUnit(const calib::UnitOutcome& u) {
  PrintUnitOutcome(u);
  std::cout << "  report: " << u.report.string() << "\n";
}

// Prints the summary; returns the exit status.
int PrintSummary(const calib::CampaignResult& result) {
  bool all_accepted = result.refused_units.empty();
  for (const calib::UnitOutcome& u : result.units) {
    PrintUnit(u);
    if (!u.acceptance || !u.acceptance->pass()) all_accepted = false;
  }
  for (const std::string& r : result.refused_units) std::cout << "refused: " << r << "\n";
  for (const std::string& s : result.not_run) std::cout << "not run: " << s << "\n";
  uint64_t lost = 0;
  for (const calib::RunSummary& r : result.runs) {
    std::cout << fmt::format("run {}: {}, {} rows this session, {} packets lost\n",
                             r.run_dir.filename().string(),
                             r.status,
                             r.rows,
                             r.lost);
    lost += r.lost;
  }
  std::cout << "records: " << result.records_file.string() << " (adahrs units show SERIAL --db "
            << result.records_file.string() << ")\n";
  if (lost > 0) {
    std::cout << fmt::format("adahrs campaign: {} packets lost: the runs are not complete\n", lost);
    return kExitPacketsLost;
  }
  return all_accepted ? 0 : kExitUnitsNotAccepted;
}

int RunCampaignCommand(const CampaignCommandOptions& o) {
  struct sigaction action {};
  action.sa_handler = OnCampaignStopSignal;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
  const bool resume = !o.resume.empty();
  const std::filesystem::path out = std::filesystem::absolute(resume ? o.resume : o.out);
  const CampaignInputs in = resume ? ResumedCampaign(out) : NewCampaign(o, out);
  calib::CampaignOptions options;
  options.out_dir = out;
  options.imu_station_file = in.station_imu;
  options.ads_station_file = in.station_ads;
  options.sequences = in.campaign.sequences;
  options.imu_strategy = in.campaign.imu_strategy;
  options.ads_strategy = in.campaign.ads_strategy;
  options.expected_serials = in.campaign.expected_serials;
  options.specification_file = in.campaign.specification_file;
  options.software_version = ADAHRS_VERSION;
  std::cout << fmt::format(
      "campaign \"{}\" {} in {}\n", in.campaign.name, resume ? "resumed" : "started", out.string());
  ConsoleObserver observer;
  try {
    return PrintSummary(calib::RunCampaign(options, observer, g_campaign_stop));
  } catch (const calib::RunInterrupted& e) {
    std::cerr << fmt::format(
        "adahrs campaign: interrupted by signal {} ({}); the instruments are left safe; "
        "continue with: adahrs campaign --resume {}\n",
        g_campaign_signal.load(),
        e.what(),
        out.string());
    return 128 + g_campaign_signal.load();
  }
}

}  // namespace

void RegisterCampaignCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "campaign",
      "Production: calibration runs, fits, download, acceptance, reports and records of a "
      "batch on the stations, resumable (docs/campaign.md)");
  auto o = std::make_shared<CampaignCommandOptions>();
  cmd->add_option("--campaign", o->campaign_file, "Campaign file (docs/campaign.md)");
  cmd->add_option("--station-imu", o->station_imu, "Station file of the IMU bench");
  cmd->add_option("--station-ads", o->station_ads, "Station file of the ADS bench");
  cmd->add_option("--out", o->out, "Campaign directory (must be new or empty)");
  cmd->add_flag("--quick",
                o->quick,
                "Shorter variants of the campaign's sequences (docs/demo.md \"--quick\")");
  auto* resume = cmd->add_option(
      "--resume", o->resume, "Continue the campaign in this directory where it stopped");
  resume->excludes(cmd->get_option("--campaign"))
      ->excludes(cmd->get_option("--out"))
      ->excludes(cmd->get_option("--station-imu"))
      ->excludes(cmd->get_option("--station-ads"))
      ->excludes(cmd->get_option("--quick"));
  cmd->callback([o] {
    const int status = RunCampaignCommand(*o);
    if (status != 0) std::exit(status);
  });
}

}  // namespace adahrs::apps
