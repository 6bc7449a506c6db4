#include "firmware_model/target/q31_kernels.h"

#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {

void LoadQ31(DspEngine* engine, Acc acc, int32_t v) {
  engine->Lac(acc, HighWord(v), 0);
  engine->MovToAccLow(acc, LowWord(v));
}

int32_t ReadQ31(DspEngine* engine, Acc acc) {
  const int16_t high = engine->MovFromAccHigh(acc);
  const uint16_t low = engine->MovFromAccLow(acc);
  return JoinWords(high, low);
}

void ShiftAcc(DspEngine* engine, Acc acc, int32_t shift) {
  int32_t remaining = shift;
  do {
    const int32_t step = remaining > 16 ? 16 : (remaining < -16 ? -16 : remaining);
    engine->Sftac(acc, static_cast<int8_t>(step));
    remaining -= step;
  } while (remaining != 0);
}

void SftacBy(DspEngine* engine, Acc acc, int32_t shift) {
  engine->ChargeMov(1);  // the shift count into a W register
  engine->Sftac(acc, static_cast<int8_t>(shift));
}

void MulQ31(DspEngine* engine, Acc acc, int32_t a_q31, int32_t b_q31) {
  const Acc scratch = Other(acc);
  engine->ChargeMov(4);  // ah, al, bh, bl into W registers
  const int16_t ah = HighWord(a_q31);
  const uint16_t al = LowWord(a_q31);
  const int16_t bh = HighWord(b_q31);
  const uint16_t bl = LowWord(b_q31);
  const int32_t ah_bl = engine->MulSU(ah, bl);
  const int32_t bh_al = engine->MulSU(bh, al);
  LoadQ31(engine, scratch, ah_bl);
  engine->Sftac(scratch, 15);
  LoadQ31(engine, acc, bh_al);
  engine->Sftac(acc, 15);
  engine->AddAcc(acc);
  engine->Mpy(scratch, ah, bh);
  engine->AddAcc(acc);
}

int32_t NormaliseQ31(DspEngine* engine, int32_t v, int8_t v_exponent, const InputNormQ31& norm) {
  LoadQ31(engine, Acc::kA, v);
  LoadQ31(engine, Acc::kB, norm.centre);
  engine->SubAcc(Acc::kA);
  engine->ChargeMov(1);  // the shift count into a W register
  ShiftAcc(engine, Acc::kA, norm.shift - v_exponent);
  return ReadQ31(engine, Acc::kA);
}

int32_t HornerQ31(DspEngine* engine, Acc acc, const PolyQ31& poly, uint8_t degree, int32_t x_q31) {
  const Acc scratch = Other(acc);
  engine->ChargeMov(2);  // coefficient pointer and loop count
  LoadQ31(engine, acc, poly.coeff[degree].mantissa_q31);
  engine->ChargeAlu(1);  // shift = work exponent - coefficient exponent
  SftacBy(engine, acc, poly.work_exponent - poly.coeff[degree].exponent);
  int32_t y = ReadQ31(engine, acc);
  for (int32_t k = degree - 1; k >= 0; --k) {
    MulQ31(engine, acc, y, x_q31);
    LoadQ31(engine, scratch, poly.coeff[k].mantissa_q31);
    engine->ChargeAlu(1);  // shift = work exponent - coefficient exponent
    SftacBy(engine, scratch, poly.work_exponent - poly.coeff[k].exponent);
    engine->AddAcc(acc);
    y = ReadQ31(engine, acc);
    engine->ChargeAlu(1);  // DEC loop count
    engine->ChargeBranch(1);
  }
  return y;
}

uint16_t IntegerSqrt(DspEngine* engine, uint32_t radicand) {
  uint32_t root = 0;
  uint32_t bit = static_cast<uint32_t>(1) << 30;
  for (uint8_t step = 0; step < 16; ++step) {
    engine->ChargeAlu(6);  // trial = root + bit (2), compare (2), subtract (2)
    engine->ChargeBranch(1);
    const uint32_t trial = root + bit;
    root >>= 1;
    if (radicand >= trial) {
      radicand -= trial;
      root += bit;
    }
    engine->ChargeAlu(4);  // root >>= 1, bit >>= 2 on 32-bit pairs
    bit >>= 2;
  }
  return static_cast<uint16_t>(root);
}

}  // namespace adahrs::firmware_model
