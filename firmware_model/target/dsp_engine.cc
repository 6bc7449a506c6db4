#include "firmware_model/target/dsp_engine.h"

#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {
namespace {

constexpr const char* kOpNames[static_cast<uint8_t>(DspOp::kCount)] = {
    "MPY",     "MAC",     "MSC",        "LAC",     "SAC",      "SAC.R",       "SFTAC",  "ADD Acc",
    "SUB Acc", "NEG Acc", "ADD Ws,Acc", "CLR Acc", "MOV ACCx", "MUL.SS",      "MUL.SU", "MUL.UU",
    "DIVF",    "DIV.SD",  "DIV.UD",     "MOV",     "ALU",      "BRA (taken)", "CALL",   "RETURN",
};

}  // namespace

const char* DspOpName(DspOp op) { return kOpNames[static_cast<uint8_t>(op)]; }

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
