// The operator of a real lab: a person at the production PC's console. Mount() and Prompt() print
// what to do and wait for Enter; end of input (Ctrl-D, a closed pipe) means the operator aborts,
// and the call throws InstrumentError kRefused (role "operator", port "console").
// No timeout: a person may take as long as the job needs.
// Left out: any confirmation that the units really are in the orientation asked (the executor's
// gravity interlock checks that, not the operator).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "hil/instruments/instruments.h"

namespace adahrs::hil {

class ConsoleOperator : public Operator {
 public:
  /// Reads confirmations from `in`, prints instructions to `out`.
  ConsoleOperator(std::istream& in, std::ostream& out);

  void Mount(const std::vector<std::string>& unit_roles, int orientation_code) override;
  void Prompt(const std::string& text) override;

 private:
  void WaitForEnter(const std::string& command);

  std::istream& in_;
  std::ostream& out_;
};

}  // namespace adahrs::hil
