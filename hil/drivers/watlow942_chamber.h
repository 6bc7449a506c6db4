// ADS bench chamber driver: a Watlow Series 942 on its XON/XOFF ASCII protocol (shared/protocols.md
// §3.2-3.3, DOC: 942 Data Communications manual pp. 10-14, 25; docs/rig/watlow-942.md), through the
// codec hil/codecs/watlow942_codec.h, implementing Chamber without profiles (the executor drives
// this chamber by set points only, so SupportsProfiles() is false and DownloadProfile /
// StartProfile throw kRefused).
//   Identify      `? MDL`  → "942 <revision>" (anything else: kWrongIdentity)
//   ReadProcessC  `? C1`;  ReadSetPointC `? CSP`
//   SetSetPointC  `= SP1 v` (1 decimal; the mnemonic is INF, as on the 988)
//   Hold          `? MODE`; if running (1), `= HOLD 1` (the set point of the moment is held)
// The 942 never reports errors on this framing (p. 25): every `=` is followed by `? ER2`, and a
// non-zero code (latched, cleared by the read) becomes kRefused naming the code.
// Framing: a `?` reply is `<XOFF><XON>value<CR>`; a `=` is acknowledged by XOFF on the CR and XON
// when done. With "flow": "xonxoff" in the station the serial driver consumes XON/XOFF itself (the
// host's output pauses while the 942 is busy); with "none" this driver waits for the XON. Either
// way flow-control bytes are stripped from the reply text.
// Left out: ANSI X3.28 framing (RS-422/485 multidrop), the 942's profile steps.
#pragma once

#include <string>
#include <vector>

#include "hil/drivers/instrument_port.h"
#include "hil/instruments/instruments.h"

namespace adahrs::hil {

class Watlow942Chamber : public Chamber {
 public:
  Watlow942Chamber(const InstrumentEntry& entry, const Clock& clock);

  InstrumentIdentity Identify() override;
  void SetSetPointC(double temp_c) override;
  double ReadSetPointC() override;
  double ReadProcessC() override;
  void Hold() override;

  bool SupportsProfiles() const override { return false; }
  void DownloadProfile(const std::string& name, const std::vector<F4ProfileStep>& steps) override;
  void StartProfile(const std::string& name) override;
  bool ProfileRunning() override { return false; }

 private:
  std::string Query(const std::string& mnemonic);
  double QueryNumber(const std::string& mnemonic);
  void Set(const std::string& mnemonic, double value);

  InstrumentPort port_;
};

}  // namespace adahrs::hil
