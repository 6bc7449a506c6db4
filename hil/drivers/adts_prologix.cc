#include "hil/drivers/adts_prologix.h"

#include <fmt/format.h>

#include "hil/codecs/prologix.h"
#include "hil/codecs/scpi.h"

namespace adahrs::hil {
namespace {

using Kind = InstrumentError::Kind;

// Significant digits of numbers sent: 0.01 ft at 50,000 ft.
constexpr int kNumberDigits = 9;

std::string Trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) {
    text.pop_back();
  }
  return text;
}

}  // namespace

AdtsPrologix::AdtsPrologix(const InstrumentEntry& entry, const Clock& clock)
    : port_(entry, clock) {}

void AdtsPrologix::Configure() {
  if (configured_) return;
  for (const std::string& line : {std::string("++mode 1"),
                                  fmt::format("++addr {}", port_.entry().address),
                                  std::string("++auto 0"),
                                  std::string("++eos 2"),
                                  std::string("++eoi 1"),
                                  std::string("++eot_enable 0")}) {
    port_.Send(line, line + "\n");
  }
  configured_ = true;
  Command("*CLS");
  Command("UNIT:PRES PA");
}

std::string AdtsPrologix::Query(const std::string& scpi) {
  Configure();
  const std::string request = EscapePrologixData(scpi) + "\n++read eoi\n";
  return Trim(port_.Exchange(scpi, request, "\n"));
}

double AdtsPrologix::QueryNumber(const std::string& scpi) {
  const std::string text = Query(scpi);
  if (const std::optional<double> value = ParseScpiNumber(text)) return *value;
  port_.Fail(Kind::kBadReply, scpi, text, "expected a number");
}

void AdtsPrologix::Command(const std::string& scpi) {
  Configure();
  port_.port().DiscardInput();
  port_.Send(scpi, EscapePrologixData(scpi) + "\n");
  const std::string error = Query("SYST:ERR?");
  const std::optional<double> code = ParseScpiNumber(error.substr(0, error.find(',')));
  if (!code) port_.Fail(Kind::kBadReply, scpi + "; SYST:ERR?", error, "");
  if (*code != 0.0) port_.Fail(Kind::kRefused, scpi, error, "");
}

InstrumentIdentity AdtsPrologix::Identify() {
  Configure();
  const std::string version = Trim(port_.Exchange("++ver", "++ver\n", "\n"));
  const std::string idn = Query("*IDN?");
  if (idn.find("ADTS") == std::string::npos) {
    port_.Fail(Kind::kWrongIdentity, "*IDN?", idn, "not a Druck ADTS");
  }
  return {"Druck ADTS via Prologix", idn + "; adapter: " + version};
}

void AdtsPrologix::SetAltitude(double alt_ft, double rate_ft_per_min) {
  Command("SOUR:STAT ON");
  Command("SOUR:RATE ALT," + FormatScpiNumber(rate_ft_per_min, kNumberDigits));
  Command("SOUR:PRES ALT," + FormatScpiNumber(alt_ft, kNumberDigits));
}

void AdtsPrologix::SetAirspeed(double cas_kt, double rate_kt_per_min) {
  Command("SOUR:STAT ON");
  Command("SOUR:RATE CAS," + FormatScpiNumber(rate_kt_per_min, kNumberDigits));
  Command("SOUR:PRES CAS," + FormatScpiNumber(cas_kt, kNumberDigits));
}

bool AdtsPrologix::Stable() {
  const double value = QueryNumber("STAT:OPER:COND?");
  if (value < 0 || value != static_cast<int>(value)) {
    port_.Fail(
        Kind::kBadReply, "STAT:OPER:COND?", fmt::format("{:g}", value), "expected a register");
  }
  const int bits = static_cast<int>(value);
  const int stable =
      (1 << kAdtsStableBit) | (1 << kAdtsPsAtSetPointBit) | (1 << kAdtsPtAtSetPointBit);
  return (bits & stable) == stable;
}

AirDataReading AdtsPrologix::Read() {
  AirDataReading reading;
  reading.ps_pa = QueryNumber("MEAS:PRES? PS");
  reading.qc_pa = QueryNumber("MEAS:PRES? QC");
  return reading;
}

void AdtsPrologix::GoToGround() {
  Command("SOUR:STAT ON");
  Command("SOUR:GTGR");
}

}  // namespace adahrs::hil
