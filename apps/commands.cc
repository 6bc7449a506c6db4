#include "apps/commands.h"

namespace adahrs::apps {

void RegisterCommands(CLI::App& app) {
  RegisterVersionCommand(app);
  RegisterSimulateCommand(app);
  RegisterRigCommand(app);
  RegisterSequenceCommand(app);
  RegisterRunCommand(app);
  RegisterPortsCommand(app);
}

}  // namespace adahrs::apps
