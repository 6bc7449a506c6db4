#include "rig_sim/watlow_f4.h"

#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

using hil::modbus::ExceptionCode;
using hil::modbus::ReadRequest;
using hil::modbus::Response;
using hil::modbus::WriteMultipleRequest;
using hil::modbus::WriteSingleRequest;

constexpr double kTick_s = 0.1;

// Register values in the F4's format: signed, one implied decimal (shared/protocols.md §2.2).
uint16_t Tenths(double c) {
  return static_cast<uint16_t>(static_cast<int16_t>(std::lround(c * 10)));
}

std::optional<ExceptionCode> Write(WatlowF4& f4, uint16_t reg, uint16_t value) {
  const Response r = f4.Handle(WriteSingleRequest(1, reg, value));
  if (r.is_exception) return r.exception;
  EXPECT_EQ(r.start_register, reg);
  EXPECT_EQ(r.values.at(0), value);
  return std::nullopt;
}

uint16_t Read(WatlowF4& f4, uint16_t reg) {
  const Response r = f4.Handle(ReadRequest(1, reg, 1));
  EXPECT_FALSE(r.is_exception) << "register " << reg;
  return r.is_exception ? 0xFFFF : r.values.at(0);
}

// One profile step as a client describes it (shared/protocols.md §2.4 register meanings).
struct StepSpec {
  uint16_t type;
  int duration_s = 0;
  double rate_c_per_min = 0.0;
  double target_c = 0.0;
  bool guaranteed_soak = false;
  uint16_t jump_step = 0;
  uint16_t jump_count = 0;
  uint16_t end_action = 0;
  double idle_c = 0.0;
};

// Downloads a profile with the ChamberConnect recipe (§2.5 DRV): create, insert each non-end
// step and write its parameters, then type the final step as end. Returns the profile number.
uint16_t Download(WatlowF4& f4, const std::vector<StepSpec>& steps) {
  EXPECT_EQ(Write(f4, 4002, 1), std::nullopt);
  const uint16_t profile = Read(f4, 4000);
  for (size_t i = 0; i < steps.size(); ++i) {
    const StepSpec& s = steps[i];
    const uint16_t number = static_cast<uint16_t>(i + 1);
    const bool last = i + 1 == steps.size();
    const Response selected = f4.Handle(WriteMultipleRequest(
        1, 4001, last ? std::vector<uint16_t>{number} : std::vector<uint16_t>{number, 2}));
    EXPECT_FALSE(selected.is_exception) << "step " << number;
    EXPECT_EQ(Write(f4, 4003, s.type), std::nullopt);
    switch (s.type) {
      case WatlowF4::kRampTime:
      case WatlowF4::kSoak: {
        const Response r =
            f4.Handle(WriteMultipleRequest(1,
                                           4009,
                                           {static_cast<uint16_t>(s.duration_s / 3600),
                                            static_cast<uint16_t>(s.duration_s / 60 % 60),
                                            static_cast<uint16_t>(s.duration_s % 60)}));
        EXPECT_FALSE(r.is_exception);
        if (s.type == WatlowF4::kRampTime) {
          EXPECT_EQ(Write(f4, 4044, Tenths(s.target_c)), std::nullopt);
        }
        break;
      }
      case WatlowF4::kRampRate:
        EXPECT_EQ(Write(f4, 4043, static_cast<uint16_t>(std::lround(s.rate_c_per_min * 10))),
                  std::nullopt);
        EXPECT_EQ(Write(f4, 4044, Tenths(s.target_c)), std::nullopt);
        break;
      case WatlowF4::kJump:
        EXPECT_FALSE(f4.Handle(WriteMultipleRequest(1, 4050, {profile, s.jump_step, s.jump_count}))
                         .is_exception);
        break;
      default:  // end
        EXPECT_EQ(Write(f4, 4060, s.end_action), std::nullopt);
        EXPECT_EQ(Write(f4, 4061, Tenths(s.idle_c)), std::nullopt);
        break;
    }
    if (s.guaranteed_soak) {
      EXPECT_EQ(Write(f4, 4048, 1), std::nullopt);
    }
  }
  EXPECT_EQ(Write(f4, 25, 0), std::nullopt);
  return profile;
}

std::optional<ExceptionCode> RunProfile(WatlowF4& f4, uint16_t profile, uint16_t step = 1) {
  const Response r = f4.Handle(WriteMultipleRequest(1, 4000, {profile, step, 5}));
  return r.is_exception ? std::optional(r.exception) : std::nullopt;
}

// Ticks with a process value that follows the working set point exactly (an ideal chamber), so
// the profile engine's timeline is checked apart from any chamber physics.
void TickIdeal(WatlowF4& f4, double duration_s) {
  const long ticks = std::lround(duration_s / kTick_s);
  for (long i = 0; i < ticks; ++i) f4.Tick(kTick_s, f4.WorkingSetPointC());
}

TEST(WatlowF4, StaticSetPointIsSignedTenthsAndRefusedOutsideItsLimits) {
  WatlowF4 f4(WatlowF4Settings{});
  EXPECT_EQ(Read(f4, 300), 250);  // 25.0 °C at power-up
  EXPECT_EQ(Write(f4, 300, Tenths(-40.0)), std::nullopt);
  EXPECT_EQ(Read(f4, 300), 0xFE70);  // −400 as a 16-bit two's complement word
  EXPECT_DOUBLE_EQ(f4.WorkingSetPointC(), -40.0);
  // Limits 602/603 default to −70.0 / 180.0 °C: the limit itself is accepted, a tenth beyond not.
  EXPECT_EQ(Write(f4, 300, Tenths(180.0)), std::nullopt);
  EXPECT_EQ(Write(f4, 300, Tenths(180.1)), ExceptionCode::kIllegalDataValue);
  EXPECT_EQ(Write(f4, 300, Tenths(-70.1)), ExceptionCode::kIllegalDataValue);
  EXPECT_DOUBLE_EQ(f4.WorkingSetPointC(), 180.0);  // a refused write changes nothing
  EXPECT_EQ(Read(f4, 602), Tenths(-70.0));
  EXPECT_EQ(Read(f4, 603), Tenths(180.0));
  EXPECT_EQ(Read(f4, 606), 1);
  EXPECT_EQ(Read(f4, 901), 1);
}

TEST(WatlowF4, LimitsCanBeNarrowedButNeverStrandTheSetPoint) {
  WatlowF4 f4(WatlowF4Settings{});
  EXPECT_EQ(Write(f4, 602, Tenths(30.0)), ExceptionCode::kIllegalDataValue);  // SP 25 below it
  EXPECT_EQ(Write(f4, 603, Tenths(100.0)), std::nullopt);
  EXPECT_EQ(Write(f4, 300, Tenths(100.1)), ExceptionCode::kIllegalDataValue);
  EXPECT_EQ(Write(f4, 603, Tenths(-80.0)), ExceptionCode::kIllegalDataValue);  // below 602
}

// What a client reads to identify the controller and its input (a public F4 client reads 0...5
// and 606...608 in one request each and decodes register 0 as "F4"), and the output power.
TEST(WatlowF4, IdentificationInputAndOutputPowerRegistersAnswer) {
  WatlowF4 f4(WatlowF4Settings{});
  const Response ident = f4.Handle(ReadRequest(1, 0, 6));
  ASSERT_FALSE(ident.is_exception);
  ASSERT_EQ(ident.values.size(), 6u);
  const std::string model = std::to_string(ident.values[0]);
  EXPECT_EQ(std::string() + static_cast<char>(std::stoi(model.substr(2))) +
                static_cast<char>(std::stoi(model.substr(0, 2))),
            "F4");
  const Response input = f4.Handle(ReadRequest(1, 606, 3));
  ASSERT_FALSE(input.is_exception);
  EXPECT_EQ(input.values, (std::vector<uint16_t>{1, 0, 0}));  // tenths, not latching, temperature
  EXPECT_EQ(Read(f4, 102), 0);                                // alarm 1: none modelled
  f4.SetOutputPower(0.4567, 0.0);
  EXPECT_EQ(Read(f4, 103), 4567);
  EXPECT_EQ(Read(f4, 107), 0);
  f4.SetOutputPower(0.0, 2.0);  // clamped to the capacity
  EXPECT_EQ(Read(f4, 103), 0);
  EXPECT_EQ(Read(f4, 107), 10000);
  EXPECT_EQ(Write(f4, 103, 0), ExceptionCode::kIllegalDataAddress);  // read-only
}

TEST(WatlowF4, ReadOnlyAndUnmappedRegistersGiveException02) {
  WatlowF4 f4(WatlowF4Settings{});
  EXPECT_EQ(Write(f4, 100, 0), ExceptionCode::kIllegalDataAddress);   // PV is read-only
  EXPECT_EQ(Write(f4, 4122, 0), ExceptionCode::kIllegalDataAddress);  // run status read-only
  EXPECT_EQ(Write(f4, 4045, 0), ExceptionCode::kIllegalDataAddress);  // channel 2 (F4S)
  const Response block = f4.Handle(ReadRequest(1, 99, 3));            // 99 is unmapped
  ASSERT_TRUE(block.is_exception);
  EXPECT_EQ(block.exception, ExceptionCode::kIllegalDataAddress);
  const Response tail = f4.Handle(ReadRequest(1, 65535, 2));  // runs past the address space
  EXPECT_EQ(tail.exception, ExceptionCode::kIllegalDataAddress);
  hil::modbus::Request input_registers = ReadRequest(1, 100, 1);
  input_registers.function = 0x04;
  EXPECT_EQ(f4.Handle(input_registers).exception, ExceptionCode::kIllegalFunction);
  EXPECT_EQ(Write(f4, 1210, 1), ExceptionCode::kIllegalDataValue);  // hold with nothing running
  EXPECT_EQ(Write(f4, 1217, 1), std::nullopt);                      // terminate always accepted
}

TEST(WatlowF4, MultipleWritesApplyInOrderUpToTheFirstRefusal) {
  WatlowF4 f4(WatlowF4Settings{});
  const Response r = f4.Handle(WriteMultipleRequest(1, 4000, {7, 0}));  // step 0 is invalid
  ASSERT_TRUE(r.is_exception);
  EXPECT_EQ(r.exception, ExceptionCode::kIllegalDataValue);
  EXPECT_EQ(Read(f4, 4000), 7);
  EXPECT_EQ(Read(f4, 4001), 1);
}

TEST(WatlowF4, ChamberConnectRecipeCreatesReadsBackAndDeletesAProfile) {
  WatlowF4 f4(WatlowF4Settings{});
  EXPECT_EQ(Read(f4, 4003), 6);  // profile 1 does not exist: type > 5 (§2.4)
  const uint16_t profile =
      Download(f4,
               {{.type = WatlowF4::kRampRate, .rate_c_per_min = 2.5, .target_c = -20.0},
                {.type = WatlowF4::kSoak, .duration_s = 3723, .guaranteed_soak = true},
                {.type = WatlowF4::kEnd, .end_action = WatlowF4::kIdle, .idle_c = 23.5}});
  EXPECT_EQ(profile, 1);
  EXPECT_EQ(Read(f4, 1218), 39);
  EXPECT_EQ(Read(f4, 1219), 256 - 3);
  const Response name = f4.Handle(WriteMultipleRequest(1, 3500, {'C', 'A', 'L', ' ', '1'}));
  EXPECT_FALSE(name.is_exception);
  EXPECT_EQ(Write(f4, 3505, 'a'), ExceptionCode::kIllegalDataValue);  // upper case only (§2.2)

  // Read the profile back as ChamberConnect does: select the step, read 4003.. as one block.
  ASSERT_EQ(Write(f4, 4001, 2), std::nullopt);
  const Response soak = f4.Handle(ReadRequest(1, 4003, 60));
  ASSERT_FALSE(soak.is_exception);
  EXPECT_EQ(soak.values[4003 - 4003], WatlowF4::kSoak);
  EXPECT_EQ(soak.values[4009 - 4003], 1);  // 3723 s = 1 h
  EXPECT_EQ(soak.values[4010 - 4003], 2);  // 2 min
  EXPECT_EQ(soak.values[4011 - 4003], 3);  // 3 s
  EXPECT_EQ(soak.values[4048 - 4003], 1);
  ASSERT_EQ(Write(f4, 4001, 1), std::nullopt);
  EXPECT_EQ(Read(f4, 4043), 25);
  EXPECT_EQ(Read(f4, 4044), Tenths(-20.0));
  ASSERT_EQ(Write(f4, 4001, 3), std::nullopt);
  EXPECT_EQ(Read(f4, 4003), WatlowF4::kEnd);
  EXPECT_EQ(Read(f4, 4061), Tenths(23.5));

  EXPECT_FALSE(f4.Handle(WriteMultipleRequest(1, 4000, {profile, 1, 3})).is_exception);
  EXPECT_EQ(Read(f4, 4003), 6);
  EXPECT_EQ(Read(f4, 1218), 40);
}

TEST(WatlowF4, RefusesStepValuesItCannotHonour) {
  WatlowF4 f4(WatlowF4Settings{});
  Download(f4, {{.type = WatlowF4::kSoak, .duration_s = 60}, {.type = WatlowF4::kEnd}});
  ASSERT_EQ(Write(f4, 4001, 1), std::nullopt);
  EXPECT_EQ(Write(f4, 4003, WatlowF4::kAutostart), ExceptionCode::kIllegalDataValue);
  EXPECT_EQ(Write(f4, 4003, 6), ExceptionCode::kIllegalDataValue);
  EXPECT_EQ(Write(f4, 4010, 60), ExceptionCode::kIllegalDataValue);  // minutes 0..59
  EXPECT_EQ(Write(f4, 4012, 1), ExceptionCode::kIllegalDataValue);   // wait-for: not modelled
  EXPECT_EQ(Write(f4, 4044, Tenths(200.0)), ExceptionCode::kIllegalDataValue);  // beyond 603
  EXPECT_EQ(Write(f4, 4017, 0), ExceptionCode::kIllegalDataAddress);  // gap in the step block
  ASSERT_EQ(Write(f4, 4001, 9), std::nullopt);
  EXPECT_EQ(Write(f4, 4009, 1), ExceptionCode::kIllegalDataValue);  // no step 9
}

TEST(WatlowF4, RunRefusesProfilesThatCannotRunAndEditsOfTheRunningProfile) {
  WatlowF4 f4(WatlowF4Settings{});
  EXPECT_EQ(RunProfile(f4, 1), ExceptionCode::kIllegalDataValue);  // no such profile
  const uint16_t zero_rate =
      Download(f4, {{.type = WatlowF4::kRampRate, .target_c = 30.0}, {.type = WatlowF4::kEnd}});
  EXPECT_EQ(RunProfile(f4, zero_rate), ExceptionCode::kIllegalDataValue);
  const uint16_t good =
      Download(f4, {{.type = WatlowF4::kSoak, .duration_s = 600}, {.type = WatlowF4::kEnd}});
  EXPECT_EQ(RunProfile(f4, good, 3), ExceptionCode::kIllegalDataValue);  // no step 3
  ASSERT_EQ(RunProfile(f4, good), std::nullopt);
  EXPECT_EQ(Read(f4, 200), 2);
  EXPECT_EQ(RunProfile(f4, good), ExceptionCode::kIllegalDataValue);  // already running
  ASSERT_EQ(Write(f4, 4000, good), std::nullopt);
  ASSERT_EQ(Write(f4, 4001, 1), std::nullopt);
  EXPECT_EQ(Write(f4, 4009, 2), ExceptionCode::kIllegalDataValue);
  EXPECT_EQ(Write(f4, 4002, 3), ExceptionCode::kIllegalDataValue);  // delete while running
}

TEST(WatlowF4, ProfileTimelineFollowsRampTimeRampRateSoakJumpAndEnd) {
  WatlowF4 f4(WatlowF4Settings{});
  // From PV 25: ramp 10 min to 85; ramp at 2 °C/min to 45 (20 min); soak 30 min; ramp 5 min to
  // 85; jump to step 2 twice; end idling at 25. Loop body 1200 + 1800 + 300 s, run three times.
  const uint16_t profile =
      Download(f4,
               {{.type = WatlowF4::kRampTime, .duration_s = 600, .target_c = 85.0},
                {.type = WatlowF4::kRampRate, .rate_c_per_min = 2.0, .target_c = 45.0},
                {.type = WatlowF4::kSoak, .duration_s = 1800},
                {.type = WatlowF4::kRampTime, .duration_s = 300, .target_c = 85.0},
                {.type = WatlowF4::kJump, .jump_step = 2, .jump_count = 2},
                {.type = WatlowF4::kEnd, .end_action = WatlowF4::kIdle, .idle_c = 25.0}});
  ASSERT_EQ(RunProfile(f4, profile), std::nullopt);
  // The engine integrates in 0.1 s ticks whose sum is exact to ~1e-12 s over hours, so set
  // points are compared to 1e-6 °C and step changes land on the expected tick.
  TickIdeal(f4, 300.0);
  EXPECT_NEAR(f4.WorkingSetPointC(), 55.0, 1e-6);  // half way from 25 to 85
  EXPECT_EQ(Read(f4, 4101), 1);
  EXPECT_EQ(Read(f4, 4120), 5);  // 5 min left
  TickIdeal(f4, 300.0 + 600.0);
  EXPECT_NEAR(f4.WorkingSetPointC(), 85.0 - 2.0 * 10.0, 1e-6);  // 10 min into the 2 °C/min ramp
  EXPECT_EQ(Read(f4, 4101), 2);
  TickIdeal(f4, 600.0 + 900.0);
  EXPECT_EQ(Read(f4, 4101), 3);
  EXPECT_EQ(Read(f4, 4122), Tenths(45.0));
  TickIdeal(f4, 900.0 + 300.0 + 600.0);  // t = 4500: second pass, 600 s into step 2
  EXPECT_EQ(Read(f4, 4101), 2);
  EXPECT_EQ(Read(f4, 4126), 1);
  EXPECT_NEAR(f4.WorkingSetPointC(), 85.0 - 2.0 * 10.0, 1e-6);
  TickIdeal(f4, 10500.0 - 4500.0 - kTick_s);  // one tick before the end
  EXPECT_EQ(f4.current_step(), 4);
  EXPECT_EQ(Read(f4, 4126), 2);
  EXPECT_EQ(Read(f4, 200), 2);
  TickIdeal(f4, kTick_s);
  EXPECT_EQ(Read(f4, 200), 0);  // ended: static mode at the idle set point
  EXPECT_EQ(Read(f4, 300), Tenths(25.0));
  EXPECT_DOUBLE_EQ(f4.WorkingSetPointC(), 25.0);
}

TEST(WatlowF4, GuaranteedSoakStopsTheStepClockWhilePvIsOutOfBand) {
  WatlowF4Settings settings;
  settings.guaranteed_soak_band_c = 1.0;
  WatlowF4 f4(settings);
  const uint16_t profile = Download(
      f4,
      {{.type = WatlowF4::kRampTime, .duration_s = 60, .target_c = 60.0, .guaranteed_soak = true},
       {.type = WatlowF4::kSoak, .duration_s = 600, .guaranteed_soak = true},
       {.type = WatlowF4::kEnd}});
  EXPECT_EQ(Read(f4, 1205), 10);
  f4.Tick(kTick_s, 25.0);  // the profile starts from the last PV the controller saw
  ASSERT_EQ(RunProfile(f4, profile), std::nullopt);
  // PV stays at 25: the ramp may lead it by the band (1 °C) and then waits.
  for (int i = 0; i < 600; ++i) f4.Tick(kTick_s, 25.0);
  EXPECT_EQ(f4.current_step(), 1);
  EXPECT_EQ(Read(f4, 4103), 1);
  EXPECT_GT(f4.WorkingSetPointC(), 25.0 + 1.0 - 35.0 / 60.0 * kTick_s - 1e-9);
  EXPECT_LE(f4.WorkingSetPointC(), 25.0 + 1.0 + 35.0 / 60.0 * kTick_s);
  // PV on the set point: the ramp completes its remaining time. It progressed while the set
  // point was within 1 °C of PV 25 at 35 °C/min: ceil(1 / (35/60 · 0.1)) = 18 ticks of 600.
  int ideal_ticks = 0;
  while (f4.current_step() == 1 && ideal_ticks < 1000) {
    f4.Tick(kTick_s, f4.WorkingSetPointC());
    ++ideal_ticks;
  }
  EXPECT_EQ(ideal_ticks, 600 - 18);
  EXPECT_EQ(f4.current_step(), 2);
  // Soak with PV 2 °C low for 300 s: no progress; 600 s of in-band time then end the profile.
  for (int i = 0; i < 3000; ++i) f4.Tick(kTick_s, 58.0);
  EXPECT_EQ(f4.current_step(), 2);
  EXPECT_EQ(Read(f4, 4120), 10);
  for (int i = 0; i < 5999; ++i) f4.Tick(kTick_s, 59.2);  // inside the 1 °C band
  EXPECT_EQ(f4.current_step(), 2);
  f4.Tick(kTick_s, 59.2);
  EXPECT_EQ(f4.current_step(), 0);
  EXPECT_EQ(Read(f4, 300), Tenths(60.0));  // end action hold: static at the last set point
}

TEST(WatlowF4, HoldFreezesTheProfileResumeContinuesTerminateReturnsToStatic) {
  WatlowF4 f4(WatlowF4Settings{});
  const uint16_t profile =
      Download(f4,
               {{.type = WatlowF4::kRampTime, .duration_s = 1000, .target_c = 125.0},
                {.type = WatlowF4::kEnd}});
  f4.Tick(kTick_s, 25.0);
  ASSERT_EQ(RunProfile(f4, profile), std::nullopt);
  TickIdeal(f4, 100.0);
  EXPECT_NEAR(f4.WorkingSetPointC(), 35.0, 1e-6);
  ASSERT_EQ(Write(f4, 1210, 1), std::nullopt);
  EXPECT_EQ(Read(f4, 200), 3);
  TickIdeal(f4, 500.0);
  EXPECT_NEAR(f4.WorkingSetPointC(), 35.0, 1e-6);
  ASSERT_EQ(Write(f4, 1209, 1), std::nullopt);
  EXPECT_EQ(Read(f4, 200), 2);
  TickIdeal(f4, 100.0);
  EXPECT_NEAR(f4.WorkingSetPointC(), 45.0, 1e-6);
  ASSERT_EQ(Write(f4, 1217, 1), std::nullopt);
  EXPECT_EQ(Read(f4, 200), 0);
  EXPECT_DOUBLE_EQ(f4.WorkingSetPointC(), 25.0);  // back to the static set point (300)
  EXPECT_EQ(Write(f4, 1209, 1), ExceptionCode::kIllegalDataValue);
}

}  // namespace
}  // namespace adahrs::rig_sim
