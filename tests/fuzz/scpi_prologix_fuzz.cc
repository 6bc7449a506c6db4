// Fuzzes the ADTS's GPIB path (hil/codecs/prologix.h, hil/codecs/scpi.h): the Prologix splitter
// on the host byte stream, `++` commands through the controller, data lines split into SCPI
// commands and parsed, with every argument read as a number and every reply number formatted.
// The codecs never throw on received bytes; nothing is caught.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hil/codecs/prologix.h"
#include "hil/codecs/scpi.h"

namespace hil = adahrs::hil;

namespace {

void ParseScpiLine(const std::string& text) {
  for (const std::string& command_text : hil::SplitScpiProgram(text)) {
    const hil::ScpiParsed parsed = hil::ParseScpiCommand(command_text);
    if (!parsed.command) {
      (void)hil::ScpiErrorMessage(parsed.error);
      continue;
    }
    (void)hil::ScpiHeadersMatch(*parsed.command, {"SOURce", "PRESsure"});
    for (const std::string& argument : parsed.command->args) {
      if (auto value = hil::ParseScpiNumber(argument)) (void)hil::FormatScpiNumber(*value, 7);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hil::PrologixLineSplitter splitter;
  hil::PrologixController controller("Prologix GPIB-USB Controller version 6.107");
  for (size_t i = 0; i < size; ++i) {
    auto line = splitter.Feed(data[i]);
    if (!line) continue;
    if (!line->is_command) {
      ParseScpiLine(line->text);
    } else if (controller.Apply(line->text).kind == hil::PrologixAction::Kind::kReset) {
      controller.Reset();
    }
  }
  return 0;
}
