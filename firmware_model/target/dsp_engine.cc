#include "firmware_model/target/dsp_engine.h"

#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {
namespace {

struct OpInfo {
  const char* name;
  uint8_t cycles;
};

// physics.md 5.1: MAC-class, LAC/SAC, SFTAC, MOV, MUL are single cycle; DIVx 19 with REPEAT #17;
// a taken branch, CALL 2; RETURN 3.
constexpr OpInfo kOps[static_cast<uint8_t>(DspOp::kCount)] = {
    {"MPY", 1},        {"MAC", 1},         {"MSC", 1},      {"LAC", 1},     {"SAC", 1},
    {"SAC.R", 1},      {"SFTAC", 1},       {"ADD Acc", 1},  {"SUB Acc", 1}, {"NEG Acc", 1},
    {"ADD Ws,Acc", 1}, {"CLR Acc", 1},     {"MOV ACCx", 1}, {"MUL.SS", 1},  {"MUL.SU", 1},
    {"MUL.UU", 1},     {"DIVF", 19},       {"DIV.SD", 19},  {"DIV.UD", 19}, {"MOV", 1},
    {"ALU", 1},        {"BRA (taken)", 2}, {"CALL", 2},     {"RETURN", 3},
};

}  // namespace

uint8_t DspOpCycles(DspOp op) { return kOps[static_cast<uint8_t>(op)].cycles; }
const char* DspOpName(DspOp op) { return kOps[static_cast<uint8_t>(op)].name; }

void DspEngine::Charge(DspOp op, uint8_t count) {
  const uint8_t i = static_cast<uint8_t>(op);
  op_counts_[i] += count;
  instructions_ += count;
  cycles_ += static_cast<uint32_t>(count) * kOps[i].cycles;
}

void DspEngine::ResetCounters() {
  cycles_ = 0;
  instructions_ = 0;
  for (uint32_t& c : op_counts_) c = 0;
}

bool DspEngine::TestAndClearSaturation() {
  Charge(DspOp::kAlu, 2);
  const bool any = sa_ || sb_;
  sa_ = false;
  sb_ = false;
  return any;
}

int64_t DspEngine::Product(int16_t a, int16_t b) const {
  // 17x17 multiplier: operands sign- or zero-extended into bit 17, 33-bit product.
  const int64_t ea = config_.unsigned_mode ? static_cast<int64_t>(static_cast<uint16_t>(a)) : a;
  const int64_t eb = config_.unsigned_mode ? static_cast<int64_t>(static_cast<uint16_t>(b)) : b;
  const int64_t p = ea * eb;
  return config_.integer_mode ? p : p * 2;
}

void DspEngine::Write(Acc acc, int64_t exact) {
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

void DspEngine::Mpy(Acc acc, int16_t a, int16_t b) {
  Charge(DspOp::kMpy, 1);
  Write(acc, Product(a, b));
}

void DspEngine::Mac(Acc acc, int16_t a, int16_t b) {
  Charge(DspOp::kMac, 1);
  Write(acc, acc_[Index(acc)] + Product(a, b));
}

void DspEngine::Msc(Acc acc, int16_t a, int16_t b) {
  Charge(DspOp::kMsc, 1);
  Write(acc, acc_[Index(acc)] - Product(a, b));
}

void DspEngine::Lac(Acc acc, int16_t word, int8_t shift) {
  Charge(DspOp::kLac, 1);
  Write(acc, ShiftArith(static_cast<int64_t>(word) * 65536, shift));
}

int16_t DspEngine::Store(Acc acc, int8_t shift, bool round) {
  // The shifted value stays 40 bits wide (the barrel shifter output), then bits 31..16 are taken.
  const int64_t shifted = SignExtend40(ShiftArith(acc_[Index(acc)], shift));
  const int64_t high =
      round ? RoundHighWord(shifted, config_.convergent_rounding) : (shifted >> 16);
  if (config_.saturate_writes) return SatQ15(high);
  return static_cast<int16_t>(static_cast<uint16_t>(static_cast<uint64_t>(high) & 0xFFFFu));
}

int16_t DspEngine::Sac(Acc acc, int8_t shift) {
  Charge(DspOp::kSac, 1);
  return Store(acc, shift, false);
}

int16_t DspEngine::SacR(Acc acc, int8_t shift) {
  Charge(DspOp::kSacR, 1);
  return Store(acc, shift, true);
}

void DspEngine::Sftac(Acc acc, int8_t shift) {
  Charge(DspOp::kSftac, 1);
  Write(acc, ShiftArith(acc_[Index(acc)], shift));
}

void DspEngine::AddAcc(Acc dst) {
  Charge(DspOp::kAddAcc, 1);
  Write(dst, acc_[Index(dst)] + acc_[Index(Other(dst))]);
}

void DspEngine::SubAcc(Acc dst) {
  Charge(DspOp::kSubAcc, 1);
  Write(dst, acc_[Index(dst)] - acc_[Index(Other(dst))]);
}

void DspEngine::NegAcc(Acc acc) {
  Charge(DspOp::kNegAcc, 1);
  Write(acc, -acc_[Index(acc)]);
}

void DspEngine::AddWordAcc(Acc acc, int16_t word, int8_t shift) {
  Charge(DspOp::kAddWordAcc, 1);
  Write(acc, acc_[Index(acc)] + ShiftArith(static_cast<int64_t>(word) * 65536, shift));
}

void DspEngine::ClrAcc(Acc acc) {
  Charge(DspOp::kClrAcc, 1);
  acc_[Index(acc)] = 0;
}

void DspEngine::MovToAccLow(Acc acc, uint16_t word) {
  Charge(DspOp::kMovAccWord, 1);
  const int64_t v = acc_[Index(acc)];
  acc_[Index(acc)] = (v - (v & 0xFFFF)) + word;
}

void DspEngine::MovToAccHigh(Acc acc, int16_t word) {
  Charge(DspOp::kMovAccWord, 1);
  const int64_t v = acc_[Index(acc)];
  acc_[Index(acc)] = static_cast<int64_t>(word) * 65536 + (v & 0xFFFF);
}

uint16_t DspEngine::MovFromAccLow(Acc acc) {
  Charge(DspOp::kMovAccWord, 1);
  return static_cast<uint16_t>(acc_[Index(acc)] & 0xFFFF);
}

int16_t DspEngine::MovFromAccHigh(Acc acc) {
  Charge(DspOp::kMovAccWord, 1);
  return static_cast<int16_t>(static_cast<uint16_t>((acc_[Index(acc)] >> 16) & 0xFFFF));
}

int16_t DspEngine::MovFromAccUpper(Acc acc) {
  Charge(DspOp::kMovAccWord, 1);
  return static_cast<int16_t>(acc_[Index(acc)] >> 32);
}

int32_t DspEngine::MulSS(int16_t a, int16_t b) {
  Charge(DspOp::kMulSS, 1);
  return static_cast<int32_t>(a) * static_cast<int32_t>(b);
}

int32_t DspEngine::MulSU(int16_t a, uint16_t b) {
  Charge(DspOp::kMulSU, 1);
  return static_cast<int32_t>(static_cast<int64_t>(a) * static_cast<int64_t>(b));
}

uint32_t DspEngine::MulUU(uint16_t a, uint16_t b) {
  Charge(DspOp::kMulUU, 1);
  return static_cast<uint32_t>(a) * static_cast<uint32_t>(b);
}

DivResult DspEngine::DivF(int16_t num, int16_t den) {
  Charge(DspOp::kDivF, 1);
  const int32_t abs_num = num < 0 ? -static_cast<int32_t>(num) : num;
  const int32_t abs_den = den < 0 ? -static_cast<int32_t>(den) : den;
  if (den == 0 || abs_num >= abs_den) {
    math_error_ = true;
    return DivResult{((num < 0) != (den < 0)) ? kQ15Min : kQ15Max, 0};
  }
  // Quotient of (num * 2^15) / den truncated toward zero; remainder has the dividend's sign.
  const int32_t dividend = static_cast<int32_t>(num) * 32768;
  return DivResult{dividend / den, dividend % den};
}

DivResult DspEngine::DivSD(int32_t num, int16_t den) {
  Charge(DspOp::kDivSD, 1);
  if (den == 0) {
    math_error_ = true;
    return DivResult{num < 0 ? INT16_MIN : INT16_MAX, 0};
  }
  const int64_t q = static_cast<int64_t>(num) / den;
  if (q > INT16_MAX || q < INT16_MIN) {
    math_error_ = true;
    return DivResult{q < 0 ? INT16_MIN : INT16_MAX, 0};
  }
  return DivResult{static_cast<int32_t>(q), static_cast<int32_t>(static_cast<int64_t>(num) % den)};
}

DivResult DspEngine::DivUD(uint32_t num, uint16_t den) {
  Charge(DspOp::kDivUD, 1);
  if (den == 0 || num / den > UINT16_MAX) {
    math_error_ = true;
    return DivResult{UINT16_MAX, 0};
  }
  return DivResult{static_cast<int32_t>(num / den), static_cast<int32_t>(num % den)};
}

}  // namespace adahrs::firmware_model
