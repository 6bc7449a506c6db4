// Registration of the adahrs subcommands; each lives in its own <name>_command.cc.
#pragma once

#include <CLI/CLI.hpp>

namespace adahrs::apps {

/// Adds every subcommand to `app`.
void RegisterCommands(CLI::App& app);

void RegisterVersionCommand(CLI::App& app);
void RegisterSimulateCommand(CLI::App& app);
void RegisterRigCommand(CLI::App& app);
void RegisterSequenceCommand(CLI::App& app);
void RegisterRecordsCommand(CLI::App& app);
void RegisterDownloadCommand(CLI::App& app);
void RegisterReportCommand(CLI::App& app);
void RegisterPortsCommand(CLI::App& app);
void RegisterRunCommand(CLI::App& app);
void RegisterDemoCommand(CLI::App& app);
void RegisterCampaignCommand(CLI::App& app);
void RegisterFitCommand(CLI::App& app);
void RegisterEvaluateCommand(CLI::App& app);
void RegisterDiagnoseCommand(CLI::App& app);
void RegisterAcceptanceCommand(CLI::App& app);
void RegisterStudyCommand(CLI::App& app);
void RegisterUnitCommand(CLI::App& app);

}  // namespace adahrs::apps
