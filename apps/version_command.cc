// adahrs version: prints the software version (recorded in every recording and constants file).
#include <iostream>

#include "apps/commands.h"

namespace adahrs::apps {

void RegisterVersionCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("version", "Print the software version");
  cmd->callback([] { std::cout << "adahrs " << ADAHRS_VERSION << "\n"; });
}

}  // namespace adahrs::apps
