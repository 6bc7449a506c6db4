#include "hil/drivers/console_operator.h"

#include <istream>
#include <ostream>

#include <fmt/format.h>

#include "hil/instruments/instrument_error.h"

namespace adahrs::hil {
namespace {

// Fixture codes (docs/sequences.md): axis digit 1 X, 2 Y, 3 Z; sign digit 1 up, 2 down.
std::string Describe(int orientation_code) {
  const int axis = orientation_code / 10;
  const int sign = orientation_code % 10;
  if (axis < 1 || axis > 3 || sign < 1 || sign > 2) return "unknown orientation";
  return fmt::format("{}{} up", sign == 1 ? "+" : "-", "XYZ"[axis - 1]);
}

}  // namespace

ConsoleOperator::ConsoleOperator(std::istream& in, std::ostream& out) : in_(in), out_(out) {}

void ConsoleOperator::WaitForEnter(const std::string& command) {
  out_ << "Press Enter when done (Ctrl-D aborts the run)." << std::endl;
  std::string line;
  if (!std::getline(in_, line)) {
    throw InstrumentError(InstrumentError::Kind::kRefused,
                          "operator",
                          "console",
                          command,
                          "",
                          "the operator aborted (end of input)");
  }
}

void ConsoleOperator::Mount(const std::vector<std::string>& unit_roles, int orientation_code) {
  std::string roles;
  for (const std::string& role : unit_roles) roles += (roles.empty() ? "" : ", ") + role;
  out_ << fmt::format("Mount {} in fixture orientation {} ({}).",
                      roles,
                      orientation_code,
                      Describe(orientation_code))
       << std::endl;
  WaitForEnter(fmt::format("mount {}", orientation_code));
}

void ConsoleOperator::Prompt(const std::string& text) {
  out_ << text << std::endl;
  WaitForEnter("prompt");
}

}  // namespace adahrs::hil
