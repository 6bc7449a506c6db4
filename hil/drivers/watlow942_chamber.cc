#include "hil/drivers/watlow942_chamber.h"

#include <algorithm>

#include <fmt/format.h>

#include "hil/codecs/watlow942_codec.h"

namespace adahrs::hil {
namespace {

using Kind = InstrumentError::Kind;

// `? MODE` value of run mode (docs/rig/watlow-942.md: 1 run, 2 hold, 34 off).
constexpr int kModeRun = 1;
// Set points are written with one decimal (the 942's default `dEC`; UNKNOWN for the lab's unit).
constexpr int kSetPointDecimals = 1;

std::string StripFlowControl(std::string text) {
  std::erase_if(text, [](char c) {
    return c == static_cast<char>(kWatlow942Xon) || c == static_cast<char>(kWatlow942Xoff) ||
           c == static_cast<char>(kWatlow942Cr) || c == '\n';
  });
  return text;
}

}  // namespace

Watlow942Chamber::Watlow942Chamber(const InstrumentEntry& entry, const Clock& clock)
    : port_(entry, clock) {}

std::string Watlow942Chamber::Query(const std::string& mnemonic) {
  const std::string request = EncodeWatlow942Request(Watlow942Command::kRead, mnemonic);
  const std::string command = "? " + mnemonic;
  return StripFlowControl(
      port_.Exchange(command, request, std::string(1, static_cast<char>(kWatlow942Cr))));
}

double Watlow942Chamber::QueryNumber(const std::string& mnemonic) {
  const std::string text = Query(mnemonic);
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  port_.Fail(Kind::kBadReply, "? " + mnemonic, text, "expected a number");
}

void Watlow942Chamber::Set(const std::string& mnemonic, double value) {
  const std::optional<std::string> number = FormatWatlow942Number(value, kSetPointDecimals);
  const std::string command = fmt::format("= {} {:.{}f}", mnemonic, value, kSetPointDecimals);
  if (!number) port_.Fail(Kind::kRefused, command, "", "the value does not fit 7 characters");
  const std::string request = EncodeWatlow942Request(Watlow942Command::kWrite, mnemonic, {*number});
  port_.port().DiscardInput();
  port_.Send(command, request);
  if (port_.entry().port.flow != SerialSettings::Flow::kSoftware) {
    // Without the serial driver's flow control, wait for the 942's XON (done processing).
    try {
      port_.port().ReadUntil(std::string(1, static_cast<char>(kWatlow942Xon)),
                             port_.reply_timeout());
    } catch (const TransportError& e) {
      port_.Fail(Kind::kNoReply, command, "", e.what());
    }
  }
  const double code = QueryNumber("ER2");
  if (code != 0.0) {
    port_.Fail(Kind::kRefused, command, fmt::format("ER2 {:g}", code), "the 942 latched an error");
  }
}

InstrumentIdentity Watlow942Chamber::Identify() {
  const std::string model = Query("MDL");
  if (model.rfind("942", 0) != 0) {
    port_.Fail(Kind::kWrongIdentity, "? MDL", model, "a Watlow 942 answers 942 <rev>");
  }
  return {"Watlow 942", "MDL " + model};
}

void Watlow942Chamber::SetSetPointC(double temp_c) { Set("SP1", temp_c); }

double Watlow942Chamber::ReadSetPointC() { return QueryNumber("CSP"); }

double Watlow942Chamber::ReadProcessC() { return QueryNumber("C1"); }

void Watlow942Chamber::Hold() {
  if (static_cast<int>(QueryNumber("MODE")) == kModeRun) Set("HOLD", 1.0);
}

void Watlow942Chamber::DownloadProfile(const std::string& name, const std::vector<F4ProfileStep>&) {
  port_.Fail(
      Kind::kRefused, "download profile " + name, "", "the Watlow 942 driver runs set points only");
}

void Watlow942Chamber::StartProfile(const std::string& name) {
  port_.Fail(
      Kind::kRefused, "start profile " + name, "", "the Watlow 942 driver runs set points only");
}

}  // namespace adahrs::hil
