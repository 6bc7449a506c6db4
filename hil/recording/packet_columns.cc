#include "hil/recording/packet_columns.h"

#include <cmath>

#include "firmware_model/unit_firmware.h"

namespace adahrs::hil {
namespace {

namespace fm = firmware_model;

double Q31ToValue(int32_t word, int exponent) {
  return std::ldexp(static_cast<double>(word), exponent - 31);
}

}  // namespace

std::array<int, 9> ImuSlotExponents(fm::ImuCompensationMode mode) {
  const int duty = fm::kDutyExponent, counts = fm::kGyroCountExponent, g = fm::kAccelGExponent;
  const int mps2 = fm::kAccelMps2Exponent, dps = fm::kRateExponent;
  switch (mode) {
    case fm::ImuCompensationMode::kRaw:
    case fm::ImuCompensationMode::kThermal:
      return {duty, duty, duty, duty, duty, duty, counts, counts, counts};
    case fm::ImuCompensationMode::kSensorCalibrated:
      return {g, g, g, g, g, g, dps, dps, dps};
    case fm::ImuCompensationMode::kFullyCalibrated:
      return {mps2, mps2, mps2, dps, dps, dps, g, g, g};
  }
  return {};
}

void SetPacketColumns(const fm::ImuDataPayload& data, ImuRecordRow& row) {
  for (int ch = 0; ch < 6; ++ch) {
    row.accel_ticks[2 * ch] = data.raw.t1_cnt[ch];
    row.accel_ticks[2 * ch + 1] = data.raw.t2_cnt[ch];
  }
  for (int i = 0; i < 3; ++i) {
    row.gyro_cnt[i] = data.raw.gyro_cnt[i];
    row.temp_cnt[i] = data.raw.temp_cnt[i];
  }
  row.mode = static_cast<uint8_t>(data.mode);
  if (data.mode == fm::ImuCompensationMode::kRaw) {
    row.comp.reset();
    row.comp_flags = 0;
    return;
  }
  const std::array<int, 9> exponents = ImuSlotExponents(data.mode);
  std::array<double, 9> comp{};
  for (size_t i = 0; i < comp.size(); ++i) {
    comp[i] = Q31ToValue(data.compensated.value[i], exponents[i]);
  }
  row.comp = comp;
  row.comp_flags = data.compensated.flags;
}

void SetPacketColumns(const fm::AdsDataPayload& data, AdsRecordRow& row) {
  row.ps_cnt = data.raw.ps_cnt;
  row.pt_cnt = data.raw.pt_cnt;
  row.ps_temp_cnt = data.raw.ps_bridge_cnt;
  row.pt_temp_cnt = data.raw.pt_bridge_cnt;
  row.oat_cnt = data.raw.oat_cnt;
  row.mode = static_cast<uint8_t>(data.mode);
  if (data.mode == fm::AdsCompensationMode::kRaw) {
    row.alt_ft.reset();
    row.cas_kt.reset();
    row.comp_flags = 0;
    return;
  }
  row.alt_ft = Q31ToValue(data.compensated.value[0], fm::kAltitudeExponent);
  row.cas_kt = Q31ToValue(data.compensated.value[1], fm::kAirspeedExponent);
  row.comp_flags = data.compensated.flags;
}

}  // namespace adahrs::hil
