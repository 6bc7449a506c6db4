#include "rig_sim/watlow_942_device.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/random.h"
#include "common/units.h"
#include "tests/rig_sim/device_bench.h"

namespace adahrs::rig_sim {
namespace {

// Drives the controller the way the rig does (device_bench.h); `frame_s` sets the granularity.
class Bench : public device_test::DeviceBench {
 public:
  explicit Bench(nlohmann::json config = DefaultWatlow942Config(), double frame_s = 0.01)
      : DeviceBench(std::move(config), MakeWatlow942Device, frame_s) {}

  // Sends `text` now and runs frames until the reply's CR (or an XON after a write) arrives;
  // returns the raw reply bytes.
  std::string Transact(const std::string& text) {
    Send(text);
    std::string reply;
    for (int i = 0; i < 100; ++i) {
      RunFor(0.01);
      if (!reply.empty() && (reply.back() == '\r' || (text[0] == '=' && reply.back() == '\x11')))
        break;
      reply += TakeAll();
    }
    return reply;
  }
  // The value text of a `?` reply.
  std::string Ask(const std::string& line) {
    return hil::DecodeWatlow942ReadReply(Transact(line + "\r")).value_or("<no reply>");
  }
  const Watlow942& controller() { return static_cast<Watlow942Device&>(device()).controller(); }
};

// The profile used below: up to 35 °C at 2 °C/min, soak 5 min, down to 25 °C at 2 °C/min,
// jump back to step 1 once, end in hold.
void WriteProfile(Bench& bench) {
  for (const char* line : {"= STP 1 1 35 2 1 0",
                           "= STP 2 2 0 5 0 0 0",
                           "= STP 3 1 25 2 0 0",
                           "= STP 4 3 1 1",
                           "= STP 5 0 0"}) {
    bench.Transact(std::string(line) + "\r");
  }
}

TEST(Watlow942Device, AnswersReadsAndWritesWithXonXoffFraming) {
  Bench bench;
  // p. 13: a write is acknowledged by XOFF then XON only; a read by XOFF XON value CR.
  EXPECT_EQ(bench.Transact("= SP1 30\r"), "\x13\x11");
  EXPECT_EQ(bench.Transact("? SP1\r"),
            "\x13\x11"
            "30.0\r");
  EXPECT_EQ(bench.Ask("? MDL"), "942 1");
  EXPECT_EQ(bench.Ask("? MODE"), "2");  // power-up: hold at the static set point
  EXPECT_EQ(bench.Ask("? C1"), "25.0");
  EXPECT_EQ(bench.Ask("? ER2"), "0");
}

TEST(Watlow942Device, RefusesLimitsAndModeErrorsThroughEr2) {
  Bench bench;
  struct Case {
    std::string line;
    int er2;
  };
  const std::vector<Case> cases = {
      {"= SP1 150", 25},             // above rH = 100 (never clamped)
      {"= SP1 -60", 25},             // below rL = -50
      {"= STP 25 0 0", 25},          // 24 steps (p. 21)
      {"= STP 2 1 30 0 1 0", 25},    // rate 0
      {"= STP 2 1 30 31 1 0", 25},   // rate above 30 °C/min
      {"= STP 2 2 0 60 0 0 0", 25},  // 60 minutes
      {"= STP 2 3 2 1", 25},         // jump forward
      {"= STP 2 1 30 5", 22},        // fields missing
      {"? XYZ", 21},
      {"= C1 20", 26},
      {"? STRT", 27},
      {"= HOLD 1", 31},  // already holding
      {"= RESU 1", 30},  // no profile in progress
      {"SP1 30", 20},
  };
  for (const Case& c : cases) {
    bench.Transact(c.line + "\r");
    EXPECT_EQ(bench.Ask("? ER2"), std::to_string(c.er2)) << c.line;
    EXPECT_EQ(bench.Ask("? ER2"), "0") << "ER2 is cleared when read (p. 25)";
  }
  EXPECT_EQ(bench.Ask("? SP1"), "25.0");  // nothing was changed by a refused write
  WriteProfile(bench);
  bench.Transact("= STRT 1\r");
  bench.Transact("= STRT 1\r");
  EXPECT_EQ(bench.Ask("? ER2"), "30");
  bench.Transact("= SP1 30\r");
  EXPECT_EQ(bench.Ask("? ER2"), "32");
}

TEST(Watlow942Device, RampsAtTheChamberCapacityToAStaticSetPoint) {
  Bench bench;
  const double t0_s = bench.now_s();
  bench.Transact("= SP1 65\r");
  bench.RunUntil(t0_s + 240.0);
  // Far from the set point the air heats at the 5 °C/min capacity (chamber_air.h): 25 + 5·4 = 45.
  // Tolerance: the command reached the controller at t0 within one 10 ms tick (0.0008 °C).
  EXPECT_NEAR(bench.env_.ads_chamber_air_c, 45.0, 0.002);
}

TEST(Watlow942Device, FollowsAProfileWithRampSoakJumpAndEnd) {
  Bench bench;
  WriteProfile(bench);
  EXPECT_EQ(bench.Ask("? ER2"), "0");
  EXPECT_EQ(bench.Ask("? STP 1"), "1 1 35.0 2.0 1 0");
  EXPECT_EQ(bench.Ask("? STP 2"), "2 2 0 5 0 0 0");
  const double t0_s = bench.now_s();
  bench.Transact("= STRT 1\r");
  // Set point timeline: ramp 0-300 s, soak 300-600 s, ramp down 600-900 s, then once more
  // 900-1800 s, end (hold) at 1800 s. Mid-ramp the set point is 25 + 2 °C/min · 150 s = 30.
  bench.RunUntil(t0_s + 150.0);
  EXPECT_EQ(bench.Ask("? CSP"), "30.0");
  EXPECT_EQ(bench.Ask("? ENSP"), "35.0");
  // A first-order air (τ = 120 s) following a ramp r from rest lags by r·τ·(1 − e^{−t/τ}):
  // at 300 s, 35 − (2/60)·120·(1 − e^{−2.5}) = 31.3283 °C. Tolerance 0.02 °C: the set point
  // moves in 10 ms steps (≤ 0.0004 °C) and the residual cycling is ≤ 0.3·e^{−3.67/0.9} = 0.005.
  bench.RunUntil(t0_s + 300.0);
  const double lag_c = 2.0 / 60.0 * 120.0 * (1.0 - std::exp(-2.5));
  EXPECT_NEAR(bench.env_.ads_chamber_air_c, 35.0 - lag_c, 0.02);
  bench.RunUntil(t0_s + 450.0);
  EXPECT_EQ(bench.Ask("? MTR"), "2 2 0 5 0 0 0");
  EXPECT_EQ(bench.Ask("? MODE"), "1");
  // End of the first soak: the remaining lag decays as e^{−300/120}; this close to the set point
  // the chamber's residual cycling (chamber_air.h) is grown in: band·e^{−|error|/(3·band)}·
  // sin(2π·t/90 s), with t the device's time since start.
  bench.RunUntil(t0_s + 600.0);
  const double mean_c = 35.0 - lag_c * std::exp(-2.5);
  const double cycling_c =
      0.3 * std::exp(-(35.0 - mean_c) / 0.9) * std::sin(2.0 * common::kPi * bench.now_s() / 90.0);
  EXPECT_NEAR(bench.env_.ads_chamber_air_c, mean_c + cycling_c, 0.02);
  bench.RunUntil(t0_s + 1050.0);  // second pass, mid-ramp up
  EXPECT_EQ(bench.Ask("? CSP"), "30.0");
  EXPECT_EQ(bench.controller().current_step(), 1);
  bench.RunUntil(t0_s + 1795.0);
  EXPECT_EQ(bench.Ask("? MODE"), "1");
  bench.RunUntil(t0_s + 1805.0);
  EXPECT_EQ(bench.Ask("? MODE"), "2");  // End 0 = hold
  EXPECT_EQ(bench.Ask("? CSP"), "25.0");
}

TEST(Watlow942Device, HoldAndResumeFreezeTheProfileClock) {
  Bench bench;
  WriteProfile(bench);
  bench.Transact("= STRT 1\r");
  const double t0_s = bench.now_s();
  bench.RunUntil(t0_s + 60.0);
  bench.Transact("= HOLD 1\r");
  bench.RunUntil(t0_s + 660.0);  // ten minutes held at 27 °C
  EXPECT_EQ(bench.Ask("? CSP"), "27.0");
  EXPECT_EQ(bench.Ask("? MODE"), "2");
  bench.Transact("= RESU 1\r");
  bench.RunUntil(t0_s + 720.0);  // one more minute of ramp: 29 °C
  EXPECT_EQ(bench.Ask("? CSP"), "29.0");
}

TEST(Watlow942Device, SameTimelineWhateverTheAdvanceGranularity) {
  std::vector<double> air_c;
  for (const double frame_s : {0.01, 0.5, 3.7}) {
    Bench bench(DefaultWatlow942Config(), frame_s);
    WriteProfile(bench);
    bench.Transact("= STRT 1\r");
    bench.RunUntil(1234.56);
    air_c.push_back(bench.env_.ads_chamber_air_c);
  }
  // Identical, not merely close: the controller runs fixed 10 ms ticks counted from t = 0.
  EXPECT_EQ(air_c[0], air_c[1]);
  EXPECT_EQ(air_c[0], air_c[2]);
}

TEST(Watlow942Device, HostXoffPausesItsOutput) {
  Bench bench;
  bench.Transact("\x13");
  bench.Transact("? C1\r");
  bench.RunFor(1.0);
  EXPECT_EQ(bench.TakeAll(), "");
  EXPECT_EQ(bench.Transact("\x11"),
            "\x13\x11"
            "25.0\r");
}

TEST(Watlow942Device, CannotReachSetPointFault) {
  Bench bench;
  EXPECT_THAT(bench.device().PhysicalFaults(), testing::ElementsAre("cannot_reach_set_point"));
  bench.device().SetPhysicalFault("cannot_reach_set_point", true);
  bench.Transact("= SP1 60\r");
  bench.RunFor(3600.0);
  EXPECT_NEAR(bench.env_.ads_chamber_air_c, 25.0, 0.31);  // ambient ± control cycling band
  EXPECT_EQ(bench.Ask("? SP1"), "60.0");                  // the controller still wants 60
  EXPECT_THROW(bench.device().SetPhysicalFault("never_stable", true), std::invalid_argument);
}

TEST(Watlow942Device, SurvivesGarbageAndKeepsAnswering) {
  Bench bench;
  common::Rng rng(19942);
  for (int burst = 0; burst < 200; ++burst) {
    std::string garbage;
    const int length = static_cast<int>(rng.Uniform(1.0, 200.0));
    for (int k = 0; k < length; ++k) garbage.push_back(static_cast<char>(rng.NextU64() & 0xFF));
    bench.Transact(garbage);
  }
  // Whatever the garbage did (it may have written parameters; XOFF may be latched), a clean
  // session — XON, CR to end any partial line, read and clear ER2 — gets correct answers.
  bench.Transact("\x11\r");
  bench.Ask("? ER2");
  bench.Transact("= SP1 42\r");
  EXPECT_EQ(bench.Ask("? ER2"), "0");
  EXPECT_EQ(bench.Ask("? SP1"), "42.0");
}

TEST(Watlow942Device, ConfigIsValidatedWithItsPath) {
  nlohmann::json config = DefaultWatlow942Config();
  config["air"]["heat_rate_c_per_s"] = 1.0;
  try {
    MakeWatlow942Device(common::ParamReader(config, "rig.json"));
    FAIL() << "an unknown key was accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("rig.json"));
    EXPECT_THAT(e.what(), testing::HasSubstr("heat_rate_c_per_s"));
  }
  config = DefaultWatlow942Config();
  config["profile_type"] = "ramp";
  EXPECT_THROW(MakeWatlow942Device(common::ParamReader(config, "rig.json")), common::ParamError);
}

}  // namespace
}  // namespace adahrs::rig_sim
