// Bit-exact host model of the dsPIC30F/33F DSP engine and the few MCU instructions the
// compensator needs, with an instruction and cycle counter (physics.md sections 5.1-5.2).
//
// Modelled: two 40-bit accumulators A and B (int64 kept sign-extended to 40 bits); the 17x17
// multiplier in fractional (product shifted left 1) or integer mode, signed or unsigned (CORCON IF
// and US); MPY / MAC / MSC; LAC / SAC / SAC.R with the -8..+7 shift; SFTAC (-16..16, positive =
// right); ADD / SUB / NEG accumulators; ADD of a 16-bit word to an accumulator; MOV to and from
// ACCxL/ACCxH/ACCxU (memory-mapped on the 30F/33F); accumulator saturation per SATA/SATB with
// ACCSAT choosing bit-39 super saturation (9.31) or bit-31 normal saturation (1.31), or none
// (40-bit wrap, SA/SB set on catastrophic overflow); sticky SA/SB and live OA/OB flags; SATDW data
// write saturation with the sign from bit 39; conventional or convergent rounding (RND);
// MUL.SS/SU/UU into a W-register pair; DIVF, DIV.SD and DIV.UD (truncated quotient and remainder,
// 19 cycles each with the REPEAT #17); and MOV, SUB/SUBB, LSR/RRC, compare-and-branch charges.
// Cycle costs (physics.md 5.1, Programmer's Reference Manual DS70157): every instruction here is
// 1 cycle except DIVx (19 incl. REPEAT), a taken branch (2), CALL (2) and RETURN (3).
// Assumptions (R): a left SFTAC/LAC shift saturates on the exact shifted value; a division whose
// quotient does not fit, or by zero, sets the math-error flag (the chip traps) and returns a
// saturated quotient. Not modelled: the X/Y prefetch AGUs and W13 write-back of MAC-class
// instructions (the compensator loads operands with explicit MOVs, which costs more, not less),
// the pipeline, interrupts, DO/REPEAT hardware beyond their cycle charge, OA/OB traps.
#pragma once

#include <cstdint>

#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {

enum class Acc : uint8_t { kA = 0, kB = 1 };

/// The other accumulator.
constexpr Acc Other(Acc acc) { return acc == Acc::kA ? Acc::kB : Acc::kA; }

/// Instruction classes counted by the engine (one entry of the cycle table each).
enum class DspOp : uint8_t {
  kMpy,
  kMac,
  kMsc,
  kLac,
  kSac,
  kSacR,
  kSftac,
  kAddAcc,
  kSubAcc,
  kNegAcc,
  kAddWordAcc,
  kClrAcc,
  kMovAccWord,
  kMulSS,
  kMulSU,
  kMulUU,
  kDivF,
  kDivSD,
  kDivUD,
  kMov,
  kAlu,
  kBranch,
  kCall,
  kReturn,
  kCount
};

// physics.md 5.1: MAC-class, LAC/SAC, SFTAC, MOV, MUL are single cycle; DIVx 19 with REPEAT #17;
// a taken branch, CALL 2; RETURN 3.
inline constexpr uint8_t kDspOpCycles[static_cast<uint8_t>(DspOp::kCount)] = {
    1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 19, 19, 19, 1, 1, 2, 2, 3};

/// Documented cycle cost of one instruction of class `op`.
constexpr uint8_t DspOpCycles(DspOp op) { return kDspOpCycles[static_cast<uint8_t>(op)]; }
/// Mnemonic of `op` for cycle tables.
const char* DspOpName(DspOp op);

/// CORCON bits that the arithmetic depends on.
struct DspConfig {
  bool integer_mode = false;        ///< IF: 1 = integer, 0 = fractional (product << 1)
  bool unsigned_mode = false;       ///< US: operands of MPY/MAC unsigned
  bool saturate_a = true;           ///< SATA
  bool saturate_b = true;           ///< SATB
  bool super_saturation = false;    ///< ACCSAT: 1 = bit-39 (9.31), 0 = bit-31 (1.31)
  bool saturate_writes = true;      ///< SATDW
  bool convergent_rounding = true;  ///< RND: 0 = convergent (reset default), 1 = conventional
};

struct DivResult {
  int32_t quotient;
  int32_t remainder;
};

class DspEngine {
 public:
  DspEngine() = default;
  explicit DspEngine(const DspConfig& config) : config_(config) {}

  const DspConfig& config() const { return config_; }
  void set_config(const DspConfig& config) { config_ = config; }

  // ---- DSP instructions (1 cycle each). Shifts: positive = right, negative = left.
  /// MPY a*b -> acc.
  void Mpy(Acc acc, int16_t a, int16_t b);
  /// MAC acc += a*b.
  void Mac(Acc acc, int16_t a, int16_t b);
  /// MSC acc -= a*b.
  void Msc(Acc acc, int16_t a, int16_t b);
  /// LAC: word into bits 31..16, sign-extended, low word cleared, then shifted by -8..+7.
  void Lac(Acc acc, int16_t word, int8_t shift);
  /// SAC: stores bits 31..16 of (acc shifted by -8..+7), truncated, with SATDW.
  int16_t Sac(Acc acc, int8_t shift);
  /// SAC.R: as Sac but rounded per RND.
  int16_t SacR(Acc acc, int8_t shift);
  /// SFTAC by -16..16.
  void Sftac(Acc acc, int8_t shift);
  /// ADD Acc: dst += other.
  void AddAcc(Acc dst);
  /// SUB Acc: dst -= other.
  void SubAcc(Acc dst);
  /// NEG Acc.
  void NegAcc(Acc acc);
  /// ADD Ws,#shift,Acc: word aligned like LAC, added to acc.
  void AddWordAcc(Acc acc, int16_t word, int8_t shift);
  /// CLR Acc.
  void ClrAcc(Acc acc);

  // ---- MOV to/from the memory-mapped accumulator words (1 cycle each, no saturation).
  void MovToAccLow(Acc acc, uint16_t word);
  void MovToAccHigh(Acc acc, int16_t word);  ///< writes bits 31..16 and sign-extends into ACCxU
  uint16_t MovFromAccLow(Acc acc);
  int16_t MovFromAccHigh(Acc acc);
  int16_t MovFromAccUpper(Acc acc);  ///< bits 39..32, sign-extended

  // ---- MCU multiply and divide.
  int32_t MulSS(int16_t a, int16_t b);
  int32_t MulSU(int16_t a, uint16_t b);
  uint32_t MulUU(uint16_t a, uint16_t b);
  /// DIVF: fractional num/den, needs |num| < |den|; quotient Q15, remainder.
  DivResult DivF(int16_t num, int16_t den);
  /// DIV.SD: signed 32/16, quotient must fit int16.
  DivResult DivSD(int32_t num, int16_t den);
  /// DIV.UD: unsigned 32/16, quotient must fit uint16.
  DivResult DivUD(uint32_t num, uint16_t den);

  // ---- Charges for plain MCU instructions whose result the caller computes itself.
  void ChargeMov(uint8_t count = 1) { Charge(DspOp::kMov, count); }
  void ChargeAlu(uint8_t count = 1) { Charge(DspOp::kAlu, count); }
  void ChargeBranch(uint8_t count = 1) { Charge(DspOp::kBranch, count); }
  /// CALL + RETURN of one subroutine.
  void ChargeCallReturn() {
    Charge(DspOp::kCall, 1);
    Charge(DspOp::kReturn, 1);
  }

  // ---- State.
  int64_t acc(Acc acc) const { return acc_[Index(acc)]; }
  /// Sets an accumulator directly (test set-up; no cycles).
  void set_acc(Acc acc, int64_t value40) { acc_[Index(acc)] = value40; }
  bool sa() const { return sa_; }
  bool sb() const { return sb_; }
  bool oa() const { return Overflowed31(acc_[0]); }
  bool ob() const { return Overflowed31(acc_[1]); }
  bool math_error() const { return math_error_; }
  /// Reads and clears SA/SB (a BTSC on SR plus a BCLR: charged 2 cycles).
  bool TestAndClearSaturation();

  uint32_t cycles() const { return cycles_; }
  uint32_t instructions() const { return instructions_; }
  uint32_t op_count(DspOp op) const { return op_counts_[static_cast<uint8_t>(op)]; }
  void ResetCounters();

 private:
  static constexpr uint8_t Index(Acc acc) { return static_cast<uint8_t>(acc); }
  static bool Overflowed31(int64_t v) {
    return v > INT64_C(0x7FFFFFFF) || v < -INT64_C(0x80000000);
  }
  void Charge(DspOp op, uint8_t count);
  int64_t Product(int16_t a, int16_t b) const;
  /// Applies the saturation mode of `acc` to an exact result and stores it.
  void Write(Acc acc, int64_t exact);
  int16_t Store(Acc acc, int8_t shift, bool round);

  DspConfig config_{};
  int64_t acc_[2] = {0, 0};
  bool sa_ = false;
  bool sb_ = false;
  bool math_error_ = false;
  uint32_t cycles_ = 0;
  uint32_t instructions_ = 0;
  uint32_t op_counts_[static_cast<uint8_t>(DspOp::kCount)] = {};
};

// The single-instruction operations are defined here so the compensator's instruction sequences
// compile to straight-line arithmetic (a call per instruction was most of the rig's time).

inline void DspEngine::Charge(DspOp op, uint8_t count) {
  const uint8_t i = static_cast<uint8_t>(op);
  op_counts_[i] += count;
  instructions_ += count;
  cycles_ += static_cast<uint32_t>(count) * kDspOpCycles[i];
}

inline int64_t DspEngine::Product(int16_t a, int16_t b) const {
  // 17x17 multiplier: operands sign- or zero-extended into bit 17, 33-bit product.
  const int64_t ea = config_.unsigned_mode ? static_cast<int64_t>(static_cast<uint16_t>(a)) : a;
  const int64_t eb = config_.unsigned_mode ? static_cast<int64_t>(static_cast<uint16_t>(b)) : b;
  const int64_t p = ea * eb;
  return config_.integer_mode ? p : p * 2;
}

inline void DspEngine::Write(Acc acc, int64_t exact) {
  const bool saturate = acc == Acc::kA ? config_.saturate_a : config_.saturate_b;
  bool& sticky = acc == Acc::kA ? sa_ : sb_;
  int64_t value = exact;
  if (saturate) {
    bool clipped = false;
    value = config_.super_saturation ? Clamp64(exact, kAcc40Min, kAcc40Max, &clipped)
                                     : Clamp64(exact, kAcc31Min, kAcc31Max, &clipped);
    if (clipped) sticky = true;
  } else {
    value = SignExtend40(exact);
    if (value != exact) sticky = true;  // catastrophic overflow past bit 39
  }
  acc_[Index(acc)] = value;
}

inline void DspEngine::Mpy(Acc acc, int16_t a, int16_t b) {
  Charge(DspOp::kMpy, 1);
  Write(acc, Product(a, b));
}

inline void DspEngine::Mac(Acc acc, int16_t a, int16_t b) {
  Charge(DspOp::kMac, 1);
  Write(acc, acc_[Index(acc)] + Product(a, b));
}

inline void DspEngine::Msc(Acc acc, int16_t a, int16_t b) {
  Charge(DspOp::kMsc, 1);
  Write(acc, acc_[Index(acc)] - Product(a, b));
}

inline void DspEngine::Lac(Acc acc, int16_t word, int8_t shift) {
  Charge(DspOp::kLac, 1);
  Write(acc, ShiftArith(static_cast<int64_t>(word) * 65536, shift));
}

inline int16_t DspEngine::Store(Acc acc, int8_t shift, bool round) {
  // The shifted value stays 40 bits wide (the barrel shifter output), then bits 31..16 are taken.
  const int64_t shifted = SignExtend40(ShiftArith(acc_[Index(acc)], shift));
  const int64_t high =
      round ? RoundHighWord(shifted, config_.convergent_rounding) : (shifted >> 16);
  if (config_.saturate_writes) return SatQ15(high);
  return static_cast<int16_t>(static_cast<uint16_t>(static_cast<uint64_t>(high) & 0xFFFFu));
}

inline int16_t DspEngine::Sac(Acc acc, int8_t shift) {
  Charge(DspOp::kSac, 1);
  return Store(acc, shift, false);
}

inline int16_t DspEngine::SacR(Acc acc, int8_t shift) {
  Charge(DspOp::kSacR, 1);
  return Store(acc, shift, true);
}

inline void DspEngine::Sftac(Acc acc, int8_t shift) {
  Charge(DspOp::kSftac, 1);
  Write(acc, ShiftArith(acc_[Index(acc)], shift));
}

inline void DspEngine::AddAcc(Acc dst) {
  Charge(DspOp::kAddAcc, 1);
  Write(dst, acc_[Index(dst)] + acc_[Index(Other(dst))]);
}

inline void DspEngine::SubAcc(Acc dst) {
  Charge(DspOp::kSubAcc, 1);
  Write(dst, acc_[Index(dst)] - acc_[Index(Other(dst))]);
}

inline void DspEngine::NegAcc(Acc acc) {
  Charge(DspOp::kNegAcc, 1);
  Write(acc, -acc_[Index(acc)]);
}

inline void DspEngine::AddWordAcc(Acc acc, int16_t word, int8_t shift) {
  Charge(DspOp::kAddWordAcc, 1);
  Write(acc, acc_[Index(acc)] + ShiftArith(static_cast<int64_t>(word) * 65536, shift));
}

inline void DspEngine::ClrAcc(Acc acc) {
  Charge(DspOp::kClrAcc, 1);
  acc_[Index(acc)] = 0;
}

inline void DspEngine::MovToAccLow(Acc acc, uint16_t word) {
  Charge(DspOp::kMovAccWord, 1);
  const int64_t v = acc_[Index(acc)];
  acc_[Index(acc)] = (v - (v & 0xFFFF)) + word;
}

inline void DspEngine::MovToAccHigh(Acc acc, int16_t word) {
  Charge(DspOp::kMovAccWord, 1);
  const int64_t v = acc_[Index(acc)];
  acc_[Index(acc)] = static_cast<int64_t>(word) * 65536 + (v & 0xFFFF);
}

inline uint16_t DspEngine::MovFromAccLow(Acc acc) {
  Charge(DspOp::kMovAccWord, 1);
  return static_cast<uint16_t>(acc_[Index(acc)] & 0xFFFF);
}

inline int16_t DspEngine::MovFromAccHigh(Acc acc) {
  Charge(DspOp::kMovAccWord, 1);
  return static_cast<int16_t>(static_cast<uint16_t>((acc_[Index(acc)] >> 16) & 0xFFFF));
}

inline int16_t DspEngine::MovFromAccUpper(Acc acc) {
  Charge(DspOp::kMovAccWord, 1);
  return static_cast<int16_t>(acc_[Index(acc)] >> 32);
}

inline int32_t DspEngine::MulSS(int16_t a, int16_t b) {
  Charge(DspOp::kMulSS, 1);
  return static_cast<int32_t>(a) * static_cast<int32_t>(b);
}

inline int32_t DspEngine::MulSU(int16_t a, uint16_t b) {
  Charge(DspOp::kMulSU, 1);
  return static_cast<int32_t>(static_cast<int64_t>(a) * static_cast<int64_t>(b));
}

inline uint32_t DspEngine::MulUU(uint16_t a, uint16_t b) {
  Charge(DspOp::kMulUU, 1);
  return static_cast<uint32_t>(a) * static_cast<uint32_t>(b);
}

}  // namespace adahrs::firmware_model
