#include "apps/commands.h"

namespace adahrs::apps {

void RegisterCommands(CLI::App& app) {
  RegisterVersionCommand(app);
  RegisterSimulateCommand(app);
  RegisterRigCommand(app);
  RegisterSequenceCommand(app);
  RegisterRecordsCommand(app);
  RegisterDownloadCommand(app);
  RegisterReportCommand(app);
  RegisterPortsCommand(app);
  RegisterRunCommand(app);
  RegisterDemoCommand(app);
  RegisterCampaignCommand(app);
  RegisterFitCommand(app);
  RegisterEvaluateCommand(app);
  RegisterDiagnoseCommand(app);
  RegisterAcceptanceCommand(app);
  RegisterStudyCommand(app);
  RegisterUnitCommand(app);
}

}  // namespace adahrs::apps
