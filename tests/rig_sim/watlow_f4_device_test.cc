#include "rig_sim/watlow_f4_device.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::rig_sim {
namespace {

using hil::modbus::DecodeResponse;
using hil::modbus::DecodeStatus;
using hil::modbus::EncodeRequest;
using hil::modbus::ReadRequest;
using hil::modbus::Response;
using hil::modbus::WriteMultipleRequest;
using hil::modbus::WriteSingleRequest;
using Bytes = std::vector<uint8_t>;

constexpr double kFrame_s = 0.01;  // the rig's world frame (rig_sim/device_host.h)
constexpr double kTick_s = 0.1;    // default control tick

uint16_t Tenths(double c) {
  return static_cast<uint16_t>(static_cast<int16_t>(std::lround(c * 10)));
}

// CRC-16/MODBUS written out again from the Serial Line spec §6.2.2, independently of the codec,
// so the garbage test judges frames by its own rule.
bool IndependentCrcOk(const Bytes& frame) {
  if (frame.size() < 4) return false;
  unsigned crc = 0xFFFF;
  for (size_t i = 0; i + 2 < frame.size(); ++i) {
    crc ^= frame[i];
    for (int k = 0; k < 8; ++k) crc = (crc & 1u) ? (crc >> 1) ^ 0xA001u : crc >> 1;
  }
  return frame[frame.size() - 2] == (crc & 0xFF) && frame[frame.size() - 1] == (crc >> 8);
}

// A device on a simulated line: frames of `dt_s`, bytes from the device collected as they are
// released, with their release time.
class Line {
 public:
  explicit Line(const WatlowF4DeviceConfig& config = {}) : device(config) {}

  void RunUntil(double until_s, double dt_s = kFrame_s) {
    // Frame instants are counted, not accumulated, so every granularity hits the same instants.
    const long frames = std::lround((until_s - now_s) / dt_s);
    const double start_s = now_s;
    for (long i = 1; i <= frames; ++i) {
      now_s = start_s + i * dt_s;
      device.Advance(now_s, dt_s, env);
      const size_t before = out.size();
      device.TakeOutput(now_s, out);
      for (size_t k = before; k < out.size(); ++k) out_times_s.push_back(now_s);
    }
  }

  void Send(const Bytes& bytes) { device.Receive(bytes, now_s); }

  // Sends a request and runs frames until a whole reply has arrived (or 1 s passed).
  Response Transact(const hil::modbus::Request& request) {
    out.clear();
    out_times_s.clear();
    Send(EncodeRequest(request));
    const double give_up_s = now_s + 1.0;
    while (now_s < give_up_s) {
      RunUntil(now_s + kFrame_s);
      const int length = hil::modbus::ResponseFrameLength(out);
      if (length > 0 && out.size() >= static_cast<size_t>(length)) break;
    }
    const auto decoded = DecodeResponse(out);
    EXPECT_EQ(decoded.status, DecodeStatus::kOk)
        << "no valid reply to a request for register " << request.start_register;
    return decoded.response;
  }

  void Write(uint16_t reg, uint16_t value) {
    const Response r = Transact(WriteSingleRequest(1, reg, value));
    EXPECT_FALSE(r.is_exception) << "write " << reg << " = " << value;
  }
  void WriteBlock(uint16_t reg, std::vector<uint16_t> values) {
    const Response r = Transact(WriteMultipleRequest(1, reg, std::move(values)));
    EXPECT_FALSE(r.is_exception) << "write block at " << reg;
  }
  uint16_t Read(uint16_t reg) {
    const Response r = Transact(ReadRequest(1, reg, 1));
    return r.values.empty() ? 0xFFFF : r.values[0];
  }

  WatlowF4Device device;
  RigEnvironment env;
  double now_s = 0.0;
  Bytes out;
  std::vector<double> out_times_s;
};

// Downloads over the line, with the ChamberConnect recipe (shared/protocols.md §2.5), the loop
// profile used below: 1 ramp 5 °C/min to 40; 2 soak 120 s (guaranteed); 3 ramp 2 °C/min to 30;
// 4 soak 120 s (guaranteed); 5 jump to step 1 twice; 6 end idling at 25. Band 0.5 °C. Then runs it.
void DownloadAndRunLoopProfile(Line& line) {
  line.Write(1205, 5);
  line.Write(4002, 1);
  const uint16_t profile = line.Read(4000);
  auto insert = [&](uint16_t step, uint16_t type) {
    line.WriteBlock(4001, {step, 2});
    line.Write(4003, type);
  };
  insert(1, WatlowF4::kRampRate);
  line.WriteBlock(4043, {50, Tenths(40.0)});
  insert(2, WatlowF4::kSoak);
  line.WriteBlock(4009, {0, 2, 0});
  line.Write(4048, 1);
  insert(3, WatlowF4::kRampRate);
  line.WriteBlock(4043, {20, Tenths(30.0)});
  insert(4, WatlowF4::kSoak);
  line.WriteBlock(4009, {0, 2, 0});
  line.Write(4048, 1);
  insert(5, WatlowF4::kJump);
  line.WriteBlock(4050, {profile, 1, 2});
  line.Write(4001, 6);
  line.Write(4003, WatlowF4::kEnd);
  line.WriteBlock(4060, {WatlowF4::kIdle, Tenths(25.0)});
  line.Write(25, 0);
  line.WriteBlock(4000, {profile, 1, 5});
}

TEST(WatlowF4Device, RepliesAfterTheInterFrameGapAtTheLineRate) {
  Line line;
  line.RunUntil(1.0);
  line.Send(EncodeRequest(ReadRequest(1, 100, 1)));
  constexpr double kStep_s = 1e-4;
  line.RunUntil(1.1, kStep_s);
  ASSERT_EQ(line.out.size(), 7u);  // address, function, byte count, 2 data, 2 CRC
  // Serial Line §2.5.1.1 at 9600 8N1: a character is 10/9600 s; the reply starts 3.5 characters
  // plus the configured 5 ms latency after the request, then one character per 10/9600 s.
  const double character_s = 10.0 / 9600.0;
  for (size_t i = 0; i < 7; ++i) {
    const double expected_s = 1.0 + 3.5 * character_s + 0.005 + (i + 1) * character_s;
    // Released at the first Advance at or after the byte's end: within one 0.1 ms step.
    EXPECT_GE(line.out_times_s[i], expected_s - 1e-9) << "byte " << i;
    EXPECT_LT(line.out_times_s[i], expected_s + kStep_s) << "byte " << i;
  }
}

TEST(WatlowF4Device, ChamberHeatsAtItsCapacityAfterASetPointWrittenOverModbus) {
  Line line;
  EXPECT_EQ(line.Read(100), Tenths(25.0));
  line.Write(300, Tenths(85.0));
  const double start_s = line.now_s;
  line.RunUntil(start_s + 360.0);
  // ChamberAir: far from the set point (error 30 °C > tau · heat rate = 120 s · 5/60 °C/s = 10 °C)
  // the air rises at the heating capacity, 5 °C/min: 25 + 30 = 55 °C after 6 min. The tolerance
  // covers the control-tick quantisation of the start (0.1 s · 5/60 °C/s) and one register LSB.
  EXPECT_NEAR(line.env.imu_chamber_air_c, 55.0, 0.1);
  EXPECT_NEAR(static_cast<int16_t>(line.Read(100)) / 10.0, 55.0, 0.1);
  EXPECT_EQ(line.Read(200), 0);
}

TEST(WatlowF4Device, OutOfLimitSetPointIsRefusedWithException03AndNothingMoves) {
  Line line;
  line.Send(EncodeRequest(WriteSingleRequest(1, 300, Tenths(200.0))));
  line.RunUntil(0.1);
  Bytes expected{0x01, 0x86, 0x03};
  hil::modbus::AppendCrc(expected);
  EXPECT_EQ(line.out, expected);
  line.RunUntil(600.0);
  EXPECT_NEAR(line.env.imu_chamber_air_c, 25.0, 0.3 + 1e-9);  // only the ±0.3 °C control band
}

TEST(WatlowF4Device, FollowsADownloadedProfileWithGuaranteedSoakAndJumpLoops) {
  Line line;
  DownloadAndRunLoopProfile(line);
  ASSERT_EQ(line.Read(200), 2);
  const double band_c = 0.5;

  // Trace one control tick at a time: the step after the tick, the air after it, and the set point.
  struct Sample {
    int step;
    double air_c;
    double sp_c;
  };
  std::vector<Sample> trace;
  const double t0_s = std::ceil(line.now_s / kTick_s) * kTick_s;
  line.RunUntil(t0_s);
  Sample previous{line.device.controller().current_step(),
                  line.device.air_c(),
                  line.device.controller().WorkingSetPointC()};
  for (int i = 0; i < 4 * 3600 * 10 && line.device.controller().current_step() != 0; ++i) {
    line.RunUntil(line.now_s + kTick_s, kTick_s);
    trace.push_back({line.device.controller().current_step(),
                     line.device.air_c(),
                     line.device.controller().WorkingSetPointC()});
  }
  ASSERT_EQ(line.device.controller().current_step(), 0) << "profile did not end in 4 h";

  // Segments of constant step.
  struct Segment {
    int step;
    size_t first, last;  // tick indices in `trace`
  };
  std::vector<Segment> segments;
  for (size_t i = 0; i < trace.size(); ++i) {
    if (segments.empty() || segments.back().step != trace[i].step) {
      segments.push_back({trace[i].step, i, i});
    }
    segments.back().last = i;
  }
  std::vector<int> order;
  for (const Segment& s : segments) order.push_back(s.step);
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3, 4, 1, 2, 3, 4, 1, 2, 3, 4, 0}));

  for (size_t k = 0; k + 1 < segments.size(); ++k) {
    const Segment& s = segments[k];
    const long ticks = static_cast<long>(s.last - s.first + 1);
    if (s.step == 1 && k == 0) {
      // The first pass began during the download, before the trace, from the PV then:
      // check its slope (5 °C/min; rounding of 0.1 s sums only) and that it reached 40.
      const double slope_c_per_min =
          (trace[s.last].sp_c - trace[s.first].sp_c) / ((s.last - s.first) * kTick_s) * 60.0;
      EXPECT_NEAR(slope_c_per_min, 5.0, 5e-9);
      EXPECT_NEAR(trace[s.last].sp_c, 40.0, 5.0 / 60.0 * kTick_s);  // within its last tick
      EXPECT_NEAR(trace[segments[k + 1].first].sp_c, 40.0, 1e-9);   // the soak holds 40
    } else if (s.step == 1) {
      // Later passes ramp from the profile set point 30 to 40 at 5 °C/min: 120 s.
      EXPECT_NEAR(ticks * kTick_s, (40.0 - 30.0) / 5.0 * 60.0, kTick_s) << "segment " << k;
    } else if (s.step == 3) {
      EXPECT_NEAR(ticks * kTick_s, (40.0 - 30.0) / 2.0 * 60.0, kTick_s) << "segment " << k;
    } else {
      // Guaranteed soak: the step lasts until 120 s have been spent with PV in the band. The
      // controller judges tick i by the air after tick i − 1; count those ticks independently.
      long in_band = 0;
      size_t end = s.first;
      for (size_t i = s.first; i <= s.last + 1 && in_band < 1200; ++i) {
        const double pv_c = i == 0 ? previous.air_c : trace[i - 1].air_c;
        if (std::abs(pv_c - trace[s.first].sp_c) <= band_c) ++in_band;
        end = i;
      }
      EXPECT_EQ(in_band, 1200) << "segment " << k;
      // The step's last tick is the 1200th in-band one (±1 tick for the boundary convention).
      EXPECT_NEAR(static_cast<double>(s.last), static_cast<double>(end), 1.0) << "segment " << k;
      // The wait is real: the chamber lags the 5 °C/min ramp (heat capacity), so soaking starts
      // late after step 1 and the step lasts longer than its 120 s.
      if (s.step == 2) {
        EXPECT_GT(ticks, 1200 + 10) << "segment " << k;
      }
      EXPECT_LE(std::abs(trace[s.last].air_c - trace[s.last].sp_c), band_c + 0.3);
    }
  }
  EXPECT_EQ(line.Read(200), 0);
  EXPECT_EQ(line.Read(300), Tenths(25.0));
}

TEST(WatlowF4Device, SameSimulatedTimelineAtAnyAdvanceGranularity) {
  std::vector<std::vector<double>> traces;
  for (double dt_s : {0.01, 0.1, 0.5, 2.0}) {
    Line line;
    DownloadAndRunLoopProfile(line);
    line.RunUntil(2.0);
    std::vector<double> samples;
    for (int k = 1; k <= 3600; ++k) {  // every 2 s for 2 h
      line.RunUntil(2.0 + 2.0 * k, dt_s);
      samples.push_back(line.env.imu_chamber_air_c);
    }
    traces.push_back(samples);
  }
  // Control ticks are counted from t = 0 whatever the Advance step, so the values are identical.
  EXPECT_GT(*std::max_element(traces[0].begin(), traces[0].end()), 39.0);  // the profile ran
  for (size_t g = 1; g < traces.size(); ++g) {
    for (size_t k = 0; k < traces[0].size(); ++k) {
      ASSERT_EQ(traces[g][k], traces[0][k]) << "granularity " << g << " at sample " << k;
    }
  }
}

TEST(WatlowF4Device, CannotReachSetPointFaultCollapsesCapacity) {
  Line line;
  EXPECT_EQ(line.device.PhysicalFaults(), std::vector<std::string>{"cannot_reach_set_point"});
  line.device.SetPhysicalFault("cannot_reach_set_point", true);
  line.Write(300, Tenths(85.0));
  const double start_s = line.now_s;
  line.RunUntil(start_s + 1200.0);
  // 5 % of the 5 °C/min capacity: 0.25 °C/min for 20 min from 25 °C (tolerance as above).
  EXPECT_NEAR(line.env.imu_chamber_air_c, 30.0, 0.05);
  EXPECT_EQ(line.Read(300), Tenths(85.0));  // the controller still asks for 85
  line.device.SetPhysicalFault("cannot_reach_set_point", false);
  line.RunUntil(line.now_s + 120.0);
  EXPECT_NEAR(line.env.imu_chamber_air_c, 40.0, 0.1);  // full capacity again: +10 °C in 2 min
  try {
    line.device.SetPhysicalFault("never_stable", true);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("imu_chamber"));
    EXPECT_THAT(e.what(), testing::HasSubstr("never_stable"));
  }
}

TEST(WatlowF4Device, UnknownFunctionGetsException01OnceTheLineIsSilent) {
  Line line;
  Bytes fc04{0x01, 0x04, 0x00, 0x64, 0x00, 0x01};
  hil::modbus::AppendCrc(fc04);
  line.Send(fc04);
  line.RunUntil(0.04);
  EXPECT_TRUE(line.out.empty());  // the frame's end is only known after the silence (50 ms)
  line.RunUntil(0.2);
  Bytes expected{0x01, 0x84, 0x01};
  hil::modbus::AppendCrc(expected);
  EXPECT_EQ(line.out, expected);
}

TEST(WatlowF4Device, BroadcastWritesAreExecutedWithoutReplyAndOtherSlavesIgnored) {
  Line line;
  line.Send(EncodeRequest(WriteSingleRequest(0, 300, Tenths(30.0))));
  line.Send(EncodeRequest(WriteSingleRequest(2, 300, Tenths(40.0))));
  line.RunUntil(0.5);
  EXPECT_TRUE(line.out.empty());
  EXPECT_EQ(line.Read(300), Tenths(30.0));
}

TEST(WatlowF4Device, RequestSplitAcrossWorldFramesIsStillServed) {
  Line line;
  const Bytes request = EncodeRequest(ReadRequest(1, 300, 1));
  line.Send(Bytes(request.begin(), request.begin() + 3));
  line.RunUntil(kFrame_s);
  line.Send(Bytes(request.begin() + 3, request.end()));
  line.RunUntil(0.1);
  EXPECT_EQ(DecodeResponse(line.out).response.values, std::vector<uint16_t>{Tenths(25.0)});
}

TEST(WatlowF4Device, RandomGarbageIsNeverAnsweredAndTheNextGoodFrameAlwaysIs) {
  Line line;
  common::Rng rng(20240604);
  int bad_frames = 0;
  for (int i = 0; i < 2000; ++i) {
    Bytes garbage;
    const int kind = static_cast<int>(rng.Uniform() * 4);
    if (kind == 0) {  // random bytes
      const int length = 1 + static_cast<int>(rng.Uniform() * 64);
      for (int k = 0; k < length; ++k) garbage.push_back(static_cast<uint8_t>(rng.NextU64()));
    } else if (kind == 1) {  // a request with 1–3 bit errors
      garbage = EncodeRequest(WriteMultipleRequest(1, 300, {Tenths(rng.Uniform(-60.0, 170.0))}));
      const int flips = 1 + static_cast<int>(rng.Uniform() * 3);
      for (int f = 0; f < flips; ++f) {
        const size_t bit = static_cast<size_t>(rng.Uniform() * 8 * garbage.size());
        garbage[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      }
    } else if (kind == 2) {  // a request cut short
      garbage = EncodeRequest(WriteSingleRequest(1, 300, Tenths(99.0)));
      garbage.resize(1 + static_cast<size_t>(rng.Uniform() * 6));
    } else {  // a request with its CRC bytes swapped or zeroed
      garbage = EncodeRequest(ReadRequest(1, 100, 1 + static_cast<uint16_t>(rng.Uniform() * 10)));
      garbage[garbage.size() - 1] ^= static_cast<uint8_t>(1 + rng.Uniform() * 254);
    }
    if (IndependentCrcOk(garbage)) continue;  // by chance a valid frame: not garbage
    ++bad_frames;
    line.out.clear();
    line.Send(garbage);
    line.RunUntil(line.now_s + 0.08);  // silence beyond the 50 ms partial-frame timeout
    ASSERT_TRUE(line.out.empty()) << "iteration " << i << " (kind " << kind << ") got a reply";
    const Response reply = line.Transact(ReadRequest(1, 300, 1));
    ASSERT_FALSE(reply.is_exception) << "iteration " << i;
    ASSERT_EQ(reply.values, std::vector<uint16_t>{Tenths(25.0)}) << "iteration " << i;
    ASSERT_TRUE(IndependentCrcOk(line.out));
  }
  EXPECT_GT(bad_frames, 1900);
}

TEST(WatlowF4DeviceConfig, DefaultSectionBuildsAndEveryKeyIsChecked) {
  const nlohmann::json config = DefaultWatlowF4Config();
  const auto device = MakeWatlowF4Device(common::ParamReader(config, "rig.json", "$.chamber"));
  EXPECT_EQ(device->role(), "imu_chamber");

  nlohmann::json typo = config;
  typo["chamber"]["heat_rate_c_per_s"] = 1.0;
  try {
    MakeWatlowF4Device(common::ParamReader(typo, "rig.json", "$.chamber"));
    FAIL() << "no exception";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("rig.json"));
    EXPECT_THAT(e.what(), testing::HasSubstr("heat_rate_c_per_s"));
  }
  nlohmann::json crossed = config;
  crossed["controller"]["set_point_low_limit_c"] = 200.0;
  try {
    MakeWatlowF4Device(common::ParamReader(crossed, "rig.json", "$.chamber"));
    FAIL() << "no exception";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("$.chamber.controller"));
    EXPECT_THAT(e.what(), testing::HasSubstr("below set_point_high_limit_c"));
  }
}

}  // namespace
}  // namespace adahrs::rig_sim
