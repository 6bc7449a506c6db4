#include "apps/commands.h"

namespace adahrs::apps {

void RegisterCommands(CLI::App& app) {
  RegisterVersionCommand(app);
  RegisterSimulateCommand(app);
}

}  // namespace adahrs::apps
