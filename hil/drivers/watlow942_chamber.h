// ADS bench chamber driver: a Watlow Series 942 on its XON/XOFF ASCII protocol (shared/protocols.md
// §3.2-3.3, DOC: 942 Data Communications manual pp. 10-14, 25; docs/rig/watlow-942.md), through the
// codec hil/codecs/watlow942_codec.h, implementing Chamber without profiles (the executor drives
// this chamber by set points only: SupportsProfiles() is false, DownloadProfile / StartProfile
// throw kRefused). Every `=` is followed by `? ER2` (the 942 reports errors nowhere else); a
// non-zero code becomes kRefused. With "flow": "xonxoff" the serial driver consumes XON/XOFF
// itself; with "none" this driver waits for the XON.
// Units: degC, one decimal on the wire.
// Commands, framing and confidence labels: docs/drivers.md ("ADS chamber").
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
