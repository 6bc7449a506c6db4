// The adahrs command: one CLI11 subcommand per job. Each subcommand only parses its options,
// calls a library and prints; the work lives in the libraries.
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "apps/commands.h"
#include "common/printable_text.h"

int main(int argc, char** argv) {
  CLI::App app{"adahrs: ADAHRS calibration HIL simulator and production calibration pipeline"};
  app.require_subcommand(1);
  adahrs::apps::RegisterCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    // Messages quote what files, instruments and operators gave; nothing of it reaches the
    // terminal as a control sequence, whichever layer forgot to quote it.
    std::cerr << "adahrs: " << adahrs::common::PrintableMessage(e.what()) << "\n";
    return 1;
  }
  return 0;
}
