#include "apps/commands.h"

namespace adahrs::apps {

void RegisterCommands(CLI::App& app) {
  RegisterVersionCommand(app);
}

}  // namespace adahrs::apps
