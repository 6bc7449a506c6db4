#include "rig_sim/rate_table_device.h"
#include "adahrs_build_paths.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/random.h"
#include "common/units.h"
#include "hil/codecs/atl_codec.h"
#include "rig_sim/device_host.h"

namespace adahrs::rig_sim {
namespace {

using ::testing::HasSubstr;

// 10 bits per byte at 9600 baud.
constexpr double kByte_s = 10.0 / 9600.0;

std::unique_ptr<SerialDevice> MakeDevice(const nlohmann::json& config = DefaultRateTableConfig()) {
  return MakeRateTableDevice(common::ParamReader(config, "test config"));
}

// Drives a device through the SerialDevice interface in world frames, as the rig does.
struct Bench {
  explicit Bench(std::unique_ptr<SerialDevice> d, double frame_s = 0.01)
      : device(std::move(d)), frame_s(frame_s) {}

  void Send(const std::string& text) {
    device->Receive({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, now_s);
  }
  void RunFor(double duration_s) {
    const double end_s = now_s + duration_s;
    while (now_s < end_s - 1e-9) {
      now_s = std::min(end_s, now_s + frame_s);
      device->Advance(now_s, frame_s, env);
      std::vector<uint8_t> out;
      device->TakeOutput(now_s, out);
      received.append(out.begin(), out.end());
    }
  }
  // Sends `text` and returns everything the device released in the next 100 ms.
  std::string Ask(const std::string& text) {
    received.clear();
    Send(text);
    RunFor(0.1);
    return received;
  }

  std::unique_ptr<SerialDevice> device;
  double frame_s;
  double now_s = 0.0;
  RigEnvironment env;
  std::string received;
};

TEST(RateTableDevice, RepliesByteForByteWithThePromptFraming) {
  Bench bench(MakeDevice());
  EXPECT_EQ(bench.Ask("JOG 100\r\n"), "\r\n>\r\n");
  EXPECT_EQ(bench.Ask("JOG?\r"), "100.000\r\n>\r\n");
  EXPECT_EQ(bench.Ask("ACL?\n"), "100.000\r\n>\r\n");
  EXPECT_EQ(bench.Ask("SRV?\r\n"), "1\r\n>\r\n");
  EXPECT_EQ(bench.Ask("CLU 3\r\nCLU?\r\n"), "\r\n>\r\n3\r\n>\r\n");
  EXPECT_EQ(bench.Ask("XYZ\r\n"), "?UNKNOWN COMMAND\r\n>\r\n");
  EXPECT_EQ(bench.Ask("JOG 1.5\r\n"), "?BAD ARGUMENT JOG\r\n>\r\n");
  EXPECT_EQ(bench.Ask(std::string(100, 'J') + "\r\n"), "?LINE TOO LONG\r\n>\r\n");
  EXPECT_EQ(bench.Ask("\r\n\r\n"), "");  // empty lines: silence
}

TEST(RateTableDevice, ReachesTheCommandedRateAndReportsIt) {
  Bench bench(MakeDevice());
  bench.Ask("JOG 100\r\n");
  const double commanded_at_s = 0.0;
  // Poll the (invented) rate query every 10 ms until it reads 100 within the 0.01 deg/s band.
  double reached_s = -1.0;
  while (bench.now_s < 5.0 && reached_s < 0) {
    const double asked_s = bench.now_s;
    const std::string reply = bench.Ask("RAT?\r\n");
    if (std::fabs(std::stod(reply) - 100.0) <= 0.01) reached_s = asked_s;
  }
  // Physics: Δr/a + tau·ln(a·tau/ε) = 1.3107 s after the command; polling every 100 ms finds it
  // up to 100 ms late, and the command took effect within one 10 ms frame.
  const double analytic_s = 1.0 + 0.05 * std::log(100.0 * 0.05 / 0.01);
  EXPECT_GE(reached_s - commanded_at_s, analytic_s);
  EXPECT_LE(reached_s - commanded_at_s, analytic_s + 0.1 + 0.02);
  // The world sees the true platter rate (ripple k = 1e-5 of 100 deg/s).
  EXPECT_NEAR(bench.env.table_rate_dps, 100.0, 100.0 * 1e-5 + 1e-9);
  EXPECT_EQ(std::stoi(bench.Ask("STA?\r\n")), 1 | 2 | 8);  // servo on, at rate, moving
}

TEST(RateTableDevice, RepliesArePacedAtTheBaudRate) {
  Bench bench(MakeDevice());
  bench.RunFor(0.5);
  bench.Send("PPO\r");
  // Release time of each byte, found by asking for output every 0.1 ms.
  std::vector<double> release_s;
  for (int i = 0; i < 300; ++i) {
    const double t_s = 0.5 + 1e-4 * (i + 1);
    bench.device->Advance(t_s, 1e-4, bench.env);
    std::vector<uint8_t> out;
    bench.device->TakeOutput(t_s, out);
    for (size_t k = 0; k < out.size(); ++k) release_s.push_back(t_s);
  }
  // "0.0000\r\n>\r\n" is 11 bytes; byte n leaves at 0.5 + latency (2 ms) + n·1.0417 ms.
  ASSERT_EQ(release_s.size(), 11u);
  for (size_t n = 0; n < release_s.size(); ++n) {
    // The 0.1 ms polling grid plus the device's 5 % of a byte of slack.
    EXPECT_NEAR(release_s[n], 0.5 + 0.002 + (n + 1) * kByte_s, 1e-4 + 0.05 * kByte_s) << n;
  }
}

TEST(RateTableDevice, OutOfLimitCommandsAreRefusedAndChangeNothing) {
  nlohmann::json config = DefaultRateTableConfig();
  config["physics"]["max_rate_dps"] = 200.0;
  Bench bench(MakeDevice(config));
  // Beyond the controller's ±360 (table) and beyond the configured ±200 drive limit.
  EXPECT_EQ(bench.Ask("JOG 500\r\n"), "?OUT OF RANGE JOG 500 LIMITS -200 200 deg/s\r\n>\r\n");
  EXPECT_EQ(bench.Ask("JOG -300\r\n"), "?OUT OF RANGE JOG -300 LIMITS -200 200 deg/s\r\n>\r\n");
  EXPECT_EQ(bench.Ask("ACL 800\r\n"), "?OUT OF RANGE ACL 800 LIMITS 0.1 500 deg/s^2\r\n>\r\n");
  EXPECT_EQ(bench.Ask("ACL 2000\r\n"), "?OUT OF RANGE ACL 2000 LIMITS 0.1 500 deg/s^2\r\n>\r\n");
  // A sine beyond the drive names the peak that breaks it: 10 deg at 10 Hz peaks at 628 deg/s;
  // 1 deg at 5 Hz at 987 deg/s^2.
  EXPECT_EQ(bench.Ask("AMP 10\r\nFRQ 10\r\nSGO\r\n"),
            "\r\n>\r\n\r\n>\r\n?OUT OF RANGE SGO 628.3185 LIMITS 0 200 deg/s\r\n>\r\n");
  EXPECT_EQ(bench.Ask("AMP 1\r\nFRQ 5\r\nSGO\r\n"),
            "\r\n>\r\n\r\n>\r\n?OUT OF RANGE SGO 986.9604 LIMITS 0 500 deg/s^2\r\n>\r\n");
  bench.RunFor(1.0);
  EXPECT_EQ(bench.Ask("JOG?\r\n"), "0.000\r\n>\r\n");
  EXPECT_EQ(bench.Ask("ACL?\r\n"), "100.000\r\n>\r\n");
  EXPECT_EQ(bench.env.table_rate_dps, 0.0);
  EXPECT_EQ(bench.Ask("JOG 200\r\n"), "\r\n>\r\n");
}

TEST(RateTableDevice, ServoAndInterlockRefusalsAndFaults) {
  Bench bench(MakeDevice());
  EXPECT_EQ(bench.Ask("SRV 0\r\n"), "\r\n>\r\n");
  EXPECT_EQ(bench.Ask("JOG 10\r\n"), "?SERVO OFF JOG\r\n>\r\n");
  EXPECT_EQ(bench.Ask("SRV 1\r\nJOG 100\r\n"), "\r\n>\r\n\r\n>\r\n");
  bench.RunFor(2.0);
  EXPECT_THAT(bench.device->PhysicalFaults(), ::testing::ElementsAre("interlock_open", "stalled"));
  bench.device->SetPhysicalFault("interlock_open", true);
  EXPECT_EQ(bench.Ask("JOG 10\r\n"), "?INTERLOCK OPEN JOG\r\n>\r\n");
  EXPECT_EQ(bench.Ask("P 10\r\n"), "?INTERLOCK OPEN P\r\n>\r\n");
  EXPECT_EQ(bench.Ask("SRV 1\r\n"), "?INTERLOCK OPEN SRV\r\n>\r\n");
  bench.RunFor(2.0);  // braked at 500 deg/s² and settled
  EXPECT_EQ(bench.env.table_rate_dps, 0.0);
  EXPECT_EQ(std::stoi(bench.Ask("STA?\r\n")), 16);  // interlock open, servo off, at rest
  bench.device->SetPhysicalFault("interlock_open", false);
  EXPECT_EQ(bench.Ask("SRV 1\r\nJOG 10\r\n"), "\r\n>\r\n\r\n>\r\n");
  try {
    bench.device->SetPhysicalFault("on_fire", true);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("rate_table: no physical fault named 'on_fire'"));
  }
}

TEST(RateTableDevice, PositionMoveEndsAtTheCommandedAngle) {
  Bench bench(MakeDevice());
  EXPECT_EQ(bench.Ask("P90\r\n"), "\r\n>\r\n");
  bench.RunFor(3.0);  // trapezoid 2.1 s plus settling
  EXPECT_EQ(bench.Ask("PPO\r\n"), "90.0000\r\n>\r\n");
  EXPECT_EQ(bench.Ask("PPO?\r\n"), "90.0000\r\n>\r\n");
  EXPECT_EQ(std::stoi(bench.Ask("STA?\r\n")), 1 | 4);  // servo on, in position
  // The world sees the true angle: the encoder error k·sin θ = 1e-5 rad·1 = 5.7e-4 deg at 90°.
  EXPECT_NEAR(bench.env.table_angle_deg, 90.0 + common::RadToDeg(1e-5), 1e-9);
  EXPECT_EQ(bench.Ask("HOM\r\n"), "\r\n>\r\n");
  bench.RunFor(3.0);
  EXPECT_EQ(bench.Ask("PPO\r\n"), "0.0000\r\n>\r\n");
  // Just short of a full turn is printed as the home it rounds to, never as 360.0000.
  EXPECT_EQ(bench.Ask("P-0.00002\r\n"), "\r\n>\r\n");
  bench.RunFor(3.0);
  EXPECT_EQ(bench.Ask("PPO?\r\n"), "0.0000\r\n>\r\n");
}

TEST(RateTableDevice, SameTimelineWhateverTheFrameLength) {
  // One script, delivered at the same simulated times to devices advanced in 10 ms frames, in
  // 1 ms frames and in 50 ms frames: the reply bytes and the world they write agree exactly.
  const std::vector<std::pair<double, std::string>> script = {{0.0, "JOG 150\r\n"},
                                                              {0.7, "RAT?\r\n"},
                                                              {1.5, "ACL 37.5\r\n"},
                                                              {2.0, "JOG -20\r\n"},
                                                              {3.1, "RAT?\r\nPPO\r\n"},
                                                              {4.0, "P 123.4\r\n"},
                                                              {6.0, "STA?\r\nPPO\r\n"},
                                                              {12.0, "PPO\r\n"}};
  auto run = [&](double frame_s) {
    Bench bench(MakeDevice(), frame_s);
    std::vector<double> rates;
    for (size_t i = 0; i <= script.size(); ++i) {
      const double until_s = i < script.size() ? script[i].first : 12.5;
      bench.RunFor(until_s - bench.now_s);
      rates.push_back(bench.env.table_rate_dps);
      rates.push_back(bench.env.table_angle_deg);
      if (i < script.size()) bench.Send(script[i].second);
    }
    return std::make_pair(bench.received, rates);
  };
  const auto frames_10ms = run(0.01);
  const auto frames_1ms = run(0.001);
  const auto frames_50ms = run(0.05);
  EXPECT_EQ(frames_10ms.first, frames_1ms.first);
  EXPECT_EQ(frames_10ms.first, frames_50ms.first);
  EXPECT_EQ(frames_10ms.second, frames_1ms.second);
  EXPECT_EQ(frames_10ms.second, frames_50ms.second);
  EXPECT_THAT(frames_10ms.first, HasSubstr("123.4000\r\n>\r\n"));
}

TEST(RateTableDevice, SurvivesRandomGarbageAndAnswersEveryLine) {
  Bench bench(MakeDevice());
  common::Rng rng(0xA71);
  const std::string alphabet = "JOGSTPACLRVUHMFQYZ?0123456789 .-+\t";
  int lines_sent = 0;  // lines the framing rules say the controller must answer
  size_t line_chars = 0;
  double max_rate_dps = 0.0;
  for (int chunk = 0; chunk < 3000; ++chunk) {
    std::string bytes;
    const int n = 1 + static_cast<int>(rng.Uniform() * 12);
    for (int i = 0; i < n; ++i) {
      const double u = rng.Uniform();
      char c;
      if (u < 0.15) {
        c = rng.Uniform() < 0.5 ? '\r' : '\n';
      } else if (u < 0.3) {
        c = static_cast<char>(static_cast<int>(rng.Uniform() * 256));  // any byte at all
      } else {
        c = alphabet[static_cast<size_t>(rng.Uniform() * alphabet.size())];
      }
      bytes.push_back(c);
      if (c == '\r' || c == '\n') {
        if (line_chars > 0) ++lines_sent;
        line_chars = 0;
      } else {
        ++line_chars;
      }
    }
    bench.Send(bytes);
    bench.RunFor(0.02);
    max_rate_dps = std::max(max_rate_dps, std::fabs(bench.env.table_rate_dps));
  }
  bench.RunFor(2.0);  // let the last replies drain at 9600 baud
  hil::AtlReplyReader reader(static_cast<RateTableDevice&>(*bench.device).commands().framing());
  const auto replies =
      reader.Push({reinterpret_cast<const uint8_t*>(bench.received.data()), bench.received.size()});
  EXPECT_EQ(static_cast<int>(replies.size()), lines_sent);
  EXPECT_EQ(reader.pending(), "");
  int errors = 0;
  for (const std::string& r : replies) errors += (!r.empty() && r[0] == '?');
  EXPECT_GT(errors, lines_sent / 2);            // mostly garbage, refused as such
  EXPECT_LE(max_rate_dps, 360.0 * (1 + 1e-5));  // never beyond the drive limit
  // Still a working controller, once the garbage's unterminated tail is ended.
  bench.Ask("\r\n");
  EXPECT_EQ(bench.Ask("SRV 1\r\nACL 100\r\nJOG 10\r\n"), "\r\n>\r\n\r\n>\r\n\r\n>\r\n");
  bench.RunFor(3.0);
  EXPECT_EQ(bench.Ask("RAT?\r\n"), "10.0000\r\n>\r\n");
}

TEST(RateTableDevice, ConfigIsCheckedKeyByKey) {
  nlohmann::json config = DefaultRateTableConfig();
  config["physics"]["max_rate_dps"] = 50.0;  // below move_rate_dps = 60
  EXPECT_THROW(MakeDevice(config), common::ParamError);
  config = DefaultRateTableConfig();
  config["baud_rate"] = 9600;
  try {
    MakeDevice(config);
    FAIL() << "accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), HasSubstr("test config: $.baud_rate: unknown key"));
  }
  config = DefaultRateTableConfig();
  config["command_table"] = "/nonexistent/atl.json";
  EXPECT_THROW(MakeDevice(config), common::ParamError);
}

TEST(RateTableDevice, ATableBindingAnUnknownOperationIsRefused) {
  nlohmann::json table = common::ParamReader::LoadFile(DefaultAtlCommandTablePath());
  table["commands"][2]["operation"] = "levitate";
  try {
    RateTableDevice device({}, hil::AtlCommandTable::FromJson(table, "lab.json"), "lab.json");
    FAIL() << "accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("lab.json: $.commands[2] (HOM): the rate table has no operation"));
  }
}

// A real outside client: pyserial opens the pty like a serial port and speaks ATL to the device
// served by the rig's DeviceHost at 20x real time (tests/rig_sim/rate_table_client.py).
TEST(RateTableDevice, PyserialSessionOverAPty) {
  DeviceHost host(20.0);
  const std::string path = host.Add(MakeDevice());
  host.Start();
  const std::string command = std::string(ADAHRS_PYTHON) + " " + ADAHRS_SOURCE_DIR +
                              "/tests/rig_sim/rate_table_client.py " + path + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = ::pclose(pipe);
  host.Stop();
  EXPECT_EQ(status, 0) << output;
  EXPECT_THAT(output, HasSubstr("ATL session OK"));
  // The client stopped the table: it waited for RAT? to print 0.0000, i.e. |rate| < 5e-5 deg/s.
  EXPECT_LT(std::fabs(host.environment().table_rate_dps), 5e-5);
}

}  // namespace
}  // namespace adahrs::rig_sim
