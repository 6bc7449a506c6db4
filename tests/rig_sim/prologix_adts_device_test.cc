#include "rig_sim/prologix_adts_device.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/air_data.h"
#include "common/atmosphere.h"
#include "common/random.h"
#include "tests/rig_sim/device_bench.h"

namespace adahrs::rig_sim {
namespace {

// Drives the device as the rig does (device_bench.h), with world frames of `frame_s`.
class Bench : public device_test::DeviceBench {
 public:
  explicit Bench(nlohmann::json config = DefaultPrologixAdtsConfig(), double frame_s = 0.01)
      : DeviceBench(std::move(config), MakePrologixAdtsDevice, frame_s) {}

  // Sends lines and collects what comes back within `wait_s`.
  std::string Talk(const std::string& text, double wait_s = 0.1) {
    Send(text);
    RunFor(wait_s);
    return TakeAll();
  }
  // The pyvisa way (protocols.md §6.2): address, write, ++read eoi.
  std::string Query(const std::string& command) {
    std::string reply = Talk("++addr 1\n" + command + "\n++read eoi\n");
    if (!reply.empty() && reply.back() == '\n') reply.pop_back();
    return reply;
  }
  int Condition() { return std::stoi(Query("STAT:OPER:COND?")); }
  const Adts405& adts() { return static_cast<PrologixAdtsDevice&>(device()).adts(); }
};

constexpr int kStable = 1 << 1, kGround = 1 << 2, kPsAtSp = 1 << 8, kPsRamp = 1 << 9,
              kPtAtSp = 1 << 10;

TEST(PrologixAdtsDevice, AnswersAPyvisaStyleSession) {
  Bench bench;
  // pyvisa-py's initialisation (protocols.md §6.2), then a query read with ++read eoi.
  EXPECT_EQ(bench.Talk("++mode 1\n++auto 0\n++read_tmo_ms 50\n++eos 3\n++eoi 1\n++eot_enable 0\n"),
            "");
  EXPECT_EQ(bench.Talk("++ver\n"), "Prologix GPIB-USB Controller version 6.107\r\n");
  EXPECT_EQ(bench.Query("*IDN?"), "DRUCK,ADTS405,0000000,V1.00");
  EXPECT_EQ(bench.Query("SOUR:STAT?"), "OFF");
  EXPECT_EQ(bench.Query("UNIT:PRES?"), "MBAR");
  // Ground at power-up: 1013.25 mbar, 0 ft, safe at ground.
  EXPECT_EQ(bench.Query("MEAS:PRES? PS"), "1013.25");
  EXPECT_EQ(bench.Query("MEAS:PRES? ALT"), "0");
  EXPECT_EQ(bench.Condition() & kGround, kGround);
  // ++auto 1 returns the answer without ++read; nobody answers at another address.
  EXPECT_EQ(bench.Talk("++auto 1\n*IDN?\n"), "DRUCK,ADTS405,0000000,V1.00\n");
  EXPECT_EQ(bench.Talk("++addr 7\n*IDN?\n"), "");
}

TEST(PrologixAdtsDevice, EosAndEoiDecideWhenTheAdtsSeesAMessage) {
  Bench bench;
  bench.Talk("++eos 3\n++eoi 0\n++addr 1\n*IDN?\n++read eoi\n");
  // No terminator and no EOI: the ADTS is still waiting for the end of the message.
  EXPECT_EQ(bench.Talk("++read eoi\n"), "");
  bench.Talk("++eos 2\n++clr\n");
  EXPECT_EQ(bench.Talk("*IDN?\n++read eoi\n"), "DRUCK,ADTS405,0000000,V1.00\n");
  // A read that times out before the response is ready returns nothing (response 20 ms).
  bench.Send("++read_tmo_ms 1\n*IDN?\n++read eoi\n");
  EXPECT_EQ(bench.TakeAll(), "");
  bench.Send("++eot_enable 1\n++eot_char 4\n++read_tmo_ms 500\n++read eoi\n");
  bench.RunFor(0.1);
  EXPECT_EQ(bench.TakeAll(), "DRUCK,ADTS405,0000000,V1.00\n\x04");
}

TEST(PrologixAdtsDevice, ReachesAimAtTheCommandedRatesAndRaisesStable15sLater) {
  Bench bench;
  bench.Talk("++eos 3\n");
  bench.Query("SOUR:STAT ON");
  bench.Query("SOUR:RATE ALT,6000");
  bench.Query("SOUR:RATE CAS,100");
  const double t0_s = bench.now_s();  // the command is acted on when its line arrives
  bench.Query("SOUR:PRES ALT,10000;SOUR:PRES CAS,250");
  // 10 000 ft at 6 000 ft/min: 100 s. 250 kt at 100 kt/min: 150 s (from ground, 0 kt).
  bench.RunUntil(t0_s + 50.0);
  // Linear in altitude: 5 000 ft at half time. Noise: 3.8/3 Pa σ ≈ 0.4 ft here; ±3 ft ≈ 7σ.
  EXPECT_NEAR(std::stod(bench.Query("MEAS:PRES? ALT")), 5000.0, 3.0);
  // Linear in CAS: 83.33 kt. Noise: 1.5 Pa σ ≈ 0.055 kt at this speed; ±0.3 kt ≈ 5σ.
  EXPECT_NEAR(std::stod(bench.Query("MEAS:PRES? CAS")), 250.0 / 3.0, 0.3);
  EXPECT_EQ(bench.Condition() & (kPsRamp | kPsAtSp), kPsRamp);
  bench.RunUntil(t0_s + 99.9);
  EXPECT_EQ(bench.Condition() & kPsAtSp, 0);
  bench.RunUntil(t0_s + 100.05);
  EXPECT_EQ(bench.Condition() & kPsAtSp, kPsAtSp);
  // ISA check value (protocols.md §5): 10 000 ft → 696.82 hPa. Noise σ 0.013 mbar; ±0.06.
  EXPECT_NEAR(std::stod(bench.Query("MEAS:PRES? PS")), 696.82, 0.06);
  bench.RunUntil(t0_s + 149.9);
  EXPECT_EQ(bench.Condition() & kPtAtSp, 0);
  bench.RunUntil(t0_s + 150.05);
  EXPECT_EQ(bench.Condition() & (kPsAtSp | kPtAtSp | kStable), kPsAtSp | kPtAtSp);
  // §5 check value: 250 kt → Qc 104.982 hPa; noise σ 0.015 mbar, ±0.07.
  EXPECT_NEAR(std::stod(bench.Query("MEAS:PRES? QC")), 104.982, 0.07);
  // Stable at aim 15 s after both at set point (§4.4): 165 s.
  bench.RunUntil(t0_s + 164.9);
  EXPECT_EQ(bench.Condition() & kStable, 0);
  bench.Query("STAT:OPER:EVEN?");  // clear the latched events
  bench.RunUntil(t0_s + 165.05);
  EXPECT_EQ(bench.Condition() & kStable, kStable);
  EXPECT_EQ(std::stoi(bench.Query("STAT:OPER:EVEN?")) & kStable, kStable);
  EXPECT_EQ(std::stoi(bench.Query("STAT:OPER:EVEN?")) & kStable, 0);  // latched, read once
  // The delivered pressures reach the units.
  EXPECT_NEAR(bench.env_.ps_pa, common::IsaStaticPressurePaFromFt(10000.0), 6.0);
  EXPECT_NEAR(bench.env_.qc_pa, common::ImpactPressurePaFromKt(250.0), 7.0);
  // Go to ground at the set rates: 10 000 ft down at 6 000 ft/min is again 100 s, 250 kt 150 s.
  bench.Query("SOUR:GTGR");
  bench.RunFor(150.1);
  EXPECT_EQ(bench.Query("SOUR:GTGR?"), "1");
}

TEST(PrologixAdtsDevice, NoiseMatchesTheControllerStabilityFigure) {
  Bench bench;
  bench.Talk("++eos 3\n");
  bench.Query("SOUR:STAT ON");
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;  // 200 s sampled every 10 ms; τ = 1 s gives ≈ 100 independent samples
  for (int i = 0; i < n; ++i) {
    bench.RunFor(0.01);
    const double e = bench.env_.ps_pa - 101325.0;
    sum += e, sum2 += e * e;
  }
  const double sigma = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  // ±0.038 mbar taken as 3σ: σ = 1.267 Pa. With ~100 independent samples the estimate's
  // relative standard error is ≈ 7 %; accept ±25 % (3.5 standard errors).
  EXPECT_NEAR(sigma, 3.8 / 3.0, 0.25 * 3.8 / 3.0);
}

TEST(PrologixAdtsDevice, RefusesLimitsWithErrorsNeverClamping) {
  Bench bench;
  bench.Talk("++eos 3\n");
  bench.Query("SOUR:STAT ON");
  struct Case {
    std::string command;
    std::string error;
  };
  const std::vector<Case> cases = {
      {"SOUR:PRES ALT,70000", "-222,\"Data out of range\""},   // above 20 km (ISA model)
      {"SOUR:PRES PS,1400", "-222,\"Data out of range\""},     // above the 1355 mbar range
      {"SOUR:PRES CAS,700", "-222,\"Data out of range\""},     // supersonic
      {"SOUR:RATE ALT,150000", "-222,\"Data out of range\""},  // > 100 000 ft/min (§4.7)
      {"SOUR:RATE CAS,2500", "-222,\"Data out of range\""},    // > 2 000 kt/min
      {"SOUR:PRES MACH,0.5", "-224,\"Illegal parameter value\""},
      {"UNIT:PRES FURLONG", "-224,\"Illegal parameter value\""},
      {"SOUR:PRES ALT,abc", "-104,\"Data type error\""},
      {"SOUR:PRES ALT", "-109,\"Missing parameter\""},
      {"CONT:PS:SETP 100", "-113,\"Undefined header\""},
  };
  for (const Case& c : cases) {
    bench.Query(c.command);
    EXPECT_EQ(bench.Query("SYST:ERR?"), c.error) << c.command;
    EXPECT_EQ(bench.Query("SYST:ERR?"), "0,\"No error\"") << c.command;
  }
  EXPECT_EQ(bench.Query("SOUR:PRES? ALT"), "0");  // the aim never moved
  EXPECT_THAT(bench.adts().unrecognised(), testing::ElementsAre("CONT:PS:SETP 100"));
  bench.Query("SOUR:STAT OFF");
  bench.Query("SOUR:GTGR");
  EXPECT_EQ(bench.Query("SYST:ERR?"), "-221,\"Settings conflict\"");  // needs control mode
}

TEST(PrologixAdtsDevice, ReportsInTheSelectedUnits) {
  Bench bench;
  bench.Talk("++eos 3\n");
  bench.Query("UNIT:PRES INHG");
  // 101325 Pa / 3386.388640341 Pa/inHg = 29.9212556 inHg (units.h definition); no noise with
  // the controllers off.
  EXPECT_EQ(bench.Query("MEAS:PRES? PS"), "29.921256");
  bench.Query("UNIT:PRES PA");
  EXPECT_EQ(bench.Query("MEAS:PRES? PT"), "101325");
  bench.Query("UNIT:PRES MMHG");
  // Conventional mmHg (13.5951 g/cm³ · g0 = 133.322387415 Pa) is not the torr (101325/760 Pa):
  // 101325 Pa = 759.99989 mmHg.
  EXPECT_EQ(bench.Query("MEAS:PRES? PS"), "759.99989");
}

TEST(PrologixAdtsDevice, NeverStableFault) {
  Bench bench;
  EXPECT_THAT(bench.device().PhysicalFaults(), testing::ElementsAre("never_stable"));
  bench.device().SetPhysicalFault("never_stable", true);
  bench.Talk("++eos 3\n");
  bench.Query("SOUR:STAT ON;SOUR:PRES ALT,1000");
  bench.RunFor(60.0);
  EXPECT_EQ(bench.Condition() & (kPsAtSp | kPtAtSp | kStable), kPsAtSp | kPtAtSp);
  bench.device().SetPhysicalFault("never_stable", false);
  bench.RunFor(0.1);
  EXPECT_EQ(bench.Condition() & kStable, kStable);
}

TEST(PrologixAdtsDevice, SameTimelineWhateverTheAdvanceGranularity) {
  std::vector<double> ps_pa, qc_pa;
  for (const double frame_s : {0.01, 0.25, 1.7}) {
    Bench bench(DefaultPrologixAdtsConfig(), frame_s);
    bench.Send(
        "++eos 3\n++addr 1\nSOUR:STAT ON;SOUR:RATE ALT,3000;SOUR:PRES ALT,2000;SOUR:PRES "
        "CAS,120\n");
    bench.RunUntil(37.77);
    ps_pa.push_back(bench.env_.ps_pa);
    qc_pa.push_back(bench.env_.qc_pa);
  }
  // Identical (noise included): the model runs fixed 10 ms ticks from t = 0.
  EXPECT_EQ(ps_pa[0], ps_pa[1]);
  EXPECT_EQ(ps_pa[0], ps_pa[2]);
  EXPECT_EQ(qc_pa[0], qc_pa[2]);
}

TEST(PrologixAdtsDevice, SurvivesGarbageAndKeepsAnswering) {
  Bench bench;
  common::Rng rng(405);
  const std::string alphabet = "+*:;?, .0123456789ABCDEFGHILMNOPRSTUV\x1b\r\n";
  for (int burst = 0; burst < 300; ++burst) {
    std::string garbage;
    const int length = static_cast<int>(rng.Uniform(1.0, 120.0));
    for (int k = 0; k < length; ++k) {
      garbage.push_back(burst % 2 ? static_cast<char>(rng.NextU64() & 0xFF)
                                  : alphabet[rng.NextU64() % alphabet.size()]);
    }
    bench.Talk(garbage, 0.02);
  }
  // A clean session after the garbage: end any partial line, reset the adapter's settings the
  // pyvisa way, clear the instrument, and the ADTS answers.
  bench.Talk(
      "\n++mode 1\n++auto 0\n++read_tmo_ms 500\n++eos 3\n++eoi 1\n++eot_enable 0\n++addr "
      "1\n++clr\n*CLS\n",
      0.5);
  EXPECT_EQ(bench.Query("*IDN?"), "DRUCK,ADTS405,0000000,V1.00");
}

// IEEE 488.2 status reporting: the event summary bit follows ESR & ESE (nothing while ESE is 0),
// the master summary bit the status byte & SRE; *ESE and *SRE read back, survive *CLS, refuse
// values outside 0...255; a query whose answer was never read is -410 with its message.
TEST(PrologixAdtsDevice, StatusByteFollowsTheEnableRegisters) {
  Bench bench;
  EXPECT_EQ(bench.Query("*ESE?"), "0");
  bench.Talk("++addr 1\nNOSUCH:HEADER\n", 0.5);  // -113: a command error, ESR bit 5
  EXPECT_EQ(bench.Query("*STB?"), "4");          // error queue only: ESE masks the summary
  bench.Talk("++addr 1\n*ESE 32\n*SRE 32\n", 0.5);
  EXPECT_EQ(bench.Query("*ESE?"), "32");
  EXPECT_EQ(bench.Query("*SRE?"), "32");
  EXPECT_EQ(bench.Query("*STB?"), std::to_string(4 | 32 | 64));
  EXPECT_EQ(bench.Query("SYST:ERR?"), "-113,\"Undefined header\"");
  bench.Talk("++addr 1\n*CLS\n*ESE 256\n", 0.5);
  EXPECT_EQ(bench.Query("SYST:ERR?"), "-224,\"Illegal parameter value\"");
  EXPECT_EQ(bench.Query("*ESE?"), "32");       // kept by *CLS, unchanged by the refused value
  bench.Talk("++addr 1\n*CLS\n*IDN?\n", 0.5);  // answered, never read ...
  bench.Talk("++addr 1\n*OPC?\n", 0.5);        // ... and replaced by the next query
  EXPECT_EQ(bench.Query("SYST:ERR?"), "-410,\"Query INTERRUPTED\"");
}

TEST(PrologixAdtsDevice, ConfigIsValidatedWithItsPath) {
  nlohmann::json config = DefaultPrologixAdtsConfig();
  config["adts"]["qc_max_pa"] = 120000.0;  // supersonic: refused
  try {
    MakePrologixAdtsDevice(common::ParamReader(config, "rig.json"));
    FAIL() << "a supersonic Qc limit was accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("qc_max_pa"));
  }
}

}  // namespace
}  // namespace adahrs::rig_sim
