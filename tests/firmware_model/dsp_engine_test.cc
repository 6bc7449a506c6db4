// Bit-exact corners of the DSP engine model; expected values are worked out by hand from the
// rules in physics.md 5.1-5.2 (dsPIC30F/33F family reference manual DSP-engine section).
#include "firmware_model/unit_firmware.h"

#include <gtest/gtest.h>

#include <cstdint>

#include "common/random.h"

namespace adahrs::firmware_model {
namespace {

DspConfig Normal() { return DspConfig{}; }  // fractional, 1.31 saturation, SATDW, convergent
DspConfig Super() {
  DspConfig c;
  c.super_saturation = true;
  return c;
}

TEST(DspEngine, MinusOneSquaredIsPlusOneIn931AndSaturatesIn131) {
  DspEngine super(Super());
  super.Mpy(Acc::kA, INT16_MIN, INT16_MIN);
  EXPECT_EQ(super.acc(Acc::kA), INT64_C(0x0080000000));  // +1.0 in 9.31
  EXPECT_FALSE(super.sa());
  EXPECT_TRUE(super.oa());  // value has spilled into the guard bits
  DspEngine normal(Normal());
  normal.Mpy(Acc::kA, INT16_MIN, INT16_MIN);
  EXPECT_EQ(normal.acc(Acc::kA), INT64_C(0x7FFFFFFF));
  EXPECT_TRUE(normal.sa());
  EXPECT_FALSE(normal.oa());  // 1.31 saturation never sets OA
}

TEST(DspEngine, IntegerModeProductIsNotShifted) {
  DspConfig c;
  c.integer_mode = true;
  DspEngine e(c);
  e.Mpy(Acc::kB, 3, -7);
  EXPECT_EQ(e.acc(Acc::kB), -21);
  DspEngine f(Normal());
  f.Mpy(Acc::kB, 3, -7);
  EXPECT_EQ(f.acc(Acc::kB), -42);
}

TEST(DspEngine, SacRoundingTiesConvergentVersusConventional) {
  DspEngine e(Normal());
  e.set_acc(Acc::kA, INT64_C(0x12348000));  // low word exactly 0x8000, bit 16 = 0
  EXPECT_EQ(e.SacR(Acc::kA, 0), 0x1234);    // tie to even: stays
  e.set_acc(Acc::kA, INT64_C(0x12358000));  // bit 16 = 1
  EXPECT_EQ(e.SacR(Acc::kA, 0), 0x1236);
  e.set_acc(Acc::kA, INT64_C(0x12348001));
  EXPECT_EQ(e.SacR(Acc::kA, 0), 0x1235);
  DspConfig conventional;
  conventional.convergent_rounding = false;
  e.set_config(conventional);
  e.set_acc(Acc::kA, INT64_C(0x12348000));
  EXPECT_EQ(e.SacR(Acc::kA, 0), 0x1235);  // biased: up on 0x8000
  e.set_acc(Acc::kA, INT64_C(0x12347FFF));
  EXPECT_EQ(e.SacR(Acc::kA, 0), 0x1234);
  // SAC without R truncates toward minus infinity.
  e.set_acc(Acc::kA, -INT64_C(0x00018000));
  EXPECT_EQ(e.Sac(Acc::kA, 0), -2);
}

TEST(DspEngine, SatdwClampsWritesWithSignFromBit39) {
  DspEngine e(Super());
  e.set_acc(Acc::kA, INT64_C(0x0080000000));  // +1.0: bits 31..16 alone read 0x8000
  EXPECT_EQ(e.Sac(Acc::kA, 0), INT16_MAX);
  e.set_acc(Acc::kA, -INT64_C(0x0080010000));  // below -1.0
  EXPECT_EQ(e.Sac(Acc::kA, 0), INT16_MIN);
  // Rounding up into overflow is caught too: 0x7FFF_C000 rounds to 0x8000 -> 0x7FFF.
  e.set_acc(Acc::kA, INT64_C(0x7FFFC000));
  EXPECT_EQ(e.SacR(Acc::kA, 0), INT16_MAX);
  DspConfig no_satdw = Super();
  no_satdw.saturate_writes = false;
  e.set_config(no_satdw);
  e.set_acc(Acc::kA, INT64_C(0x0080000000));
  EXPECT_EQ(e.Sac(Acc::kA, 0), INT16_MIN);           // the wrapped word 0x8000
  EXPECT_EQ(e.acc(Acc::kA), INT64_C(0x0080000000));  // accumulator unchanged by a store
}

TEST(DspEngine, SuperSaturationClampsAtBit39AndNoSaturationWraps) {
  DspEngine e(Super());
  e.set_acc(Acc::kA, INT64_C(0x7FFFFFFFFF) - 5);
  e.Lac(Acc::kB, 1, 0);  // +2^16
  e.AddAcc(Acc::kA);
  EXPECT_EQ(e.acc(Acc::kA), INT64_C(0x7FFFFFFFFF));
  EXPECT_TRUE(e.sa());
  DspConfig off;
  off.saturate_a = false;
  DspEngine w(off);
  w.set_acc(Acc::kA, INT64_C(0x7FFFFFFFFF));
  w.set_acc(Acc::kB, 1);
  w.AddAcc(Acc::kA);
  EXPECT_EQ(w.acc(Acc::kA), -(INT64_C(1) << 39));  // 0x80_0000_0000
  EXPECT_TRUE(w.sa());                             // catastrophic overflow is sticky
  EXPECT_TRUE(w.TestAndClearSaturation());
  EXPECT_FALSE(w.sa());
}

TEST(DspEngine, LacAndSftacShiftBothWays) {
  DspEngine e(Super());
  e.Lac(Acc::kA, -2, 3);  // -2 * 2^16 >> 3
  EXPECT_EQ(e.acc(Acc::kA), -(INT64_C(2) << 13));
  e.Sftac(Acc::kA, -16);
  EXPECT_EQ(e.acc(Acc::kA), -(INT64_C(2) << 29));
  e.Lac(Acc::kB, 0x4000, 0);
  e.Sftac(Acc::kB, -16);  // 0x4000 << 32 exceeds 9.31: clamps
  EXPECT_EQ(e.acc(Acc::kB), INT64_C(0x7FFFFFFFFF));
  EXPECT_TRUE(e.sb());
}

TEST(DspEngine, McuMultiplyAndDivide) {
  DspEngine e;
  EXPECT_EQ(e.MulSU(-1, 0xFFFF), -65535);
  EXPECT_EQ(e.MulUU(0xFFFF, 0xFFFF), 0xFFFE0001u);
  EXPECT_EQ(e.MulSS(INT16_MIN, INT16_MIN), 0x40000000);
  // DIVF: 0.5 / 0.999969 = 16384 * 32768 / 32767 = 16384.5 -> 16384 (truncated), remainder 16384.
  const DivResult q = e.DivF(0x4000, 0x7FFF);
  EXPECT_EQ(q.quotient, 16384);
  EXPECT_EQ(q.remainder, 16384);
  EXPECT_EQ(e.DivF(-0x4000, 0x7FFF).quotient, -16384);  // toward zero
  EXPECT_FALSE(e.math_error());
  e.DivF(0x4000, 0x4000);  // |num| >= |den| is outside DIVF's range
  EXPECT_TRUE(e.math_error());
  const DivResult u = DspEngine().DivUD(UINT32_C(1000) << 16, 3000);
  EXPECT_EQ(u.quotient, 21845);  // floor(65,536,000 / 3000)
  EXPECT_EQ(u.remainder, 65536000 - 21845 * 3000);
  EXPECT_EQ(DspEngine().DivSD(-100000, 7).quotient, -14285);
}

TEST(DspEngine, CycleCounterChargesDocumentedCosts) {
  DspEngine e;
  e.Mac(Acc::kA, 1, 1);
  e.DivUD(10, 3);
  e.ChargeCallReturn();
  e.ChargeBranch();
  EXPECT_EQ(e.cycles(), 1u + 19u + 2u + 3u + 2u);
  EXPECT_EQ(e.instructions(), 5u);
  EXPECT_EQ(e.op_count(DspOp::kDivUD), 1u);
  EXPECT_EQ(DspOpCycles(DspOp::kDivF), 19);
}

// MulQ31 against an independent int64 product: within [-3, 0] LSB of floor(a b / 2^31) (the
// dropped low x low term and two floors, q31_kernels.h), 15 cycles each (11 of arithmetic, 4
// MOVs of the operand words).
TEST(Q31Kernels, MulQ31WithinThreeLsbOfExactProduct) {
  common::Rng rng(31);
  for (int i = 0; i < 20000; ++i) {
    const int32_t a = static_cast<int32_t>(rng.NextU64() >> 32);
    const int32_t b = static_cast<int32_t>(rng.NextU64() >> 32);
    DspEngine e;
    MulQ31(&e, Acc::kA, a, b);
    const int64_t exact = (static_cast<int64_t>(a) * b) >> 31;
    const int64_t expected = exact > INT32_MAX ? INT32_MAX : exact;
    ASSERT_LE(e.acc(Acc::kA), expected) << a << " * " << b;
    ASSERT_GE(e.acc(Acc::kA), expected - 3) << a << " * " << b;
    ASSERT_EQ(e.cycles(), 15u);
  }
  DspEngine e;
  MulQ31(&e, Acc::kA, INT32_MIN, INT32_MIN);
  EXPECT_EQ(e.acc(Acc::kA), INT32_MAX);  // (-1)(-1) saturates under 1.31
}

}  // namespace
}  // namespace adahrs::firmware_model
