// Turns a decoded data packet's payload into the measurement columns of a recording row
// (recording_format.h): the raw inputs as the unit sent them, the mode byte, and in compensated
// modes the values in the mode's engineering units, decoded from the Q31 words as
//   value = word * 2^(exponent - 31)
// with the exponents of firmware_model/target/imu_constants.h and ads_constants.h, per slot as
// compensated_frame.h lays them out (IMU mode 1 duty and gyro counts; mode 2 g and deg/s per
// channel; mode 3 A m/s^2, G deg/s, pair disagreement g; ADS surface mode ft and kt).
// Leaves every other column (time, unit, step, tag, instrument readings) to the caller.
#pragma once

#include <array>

#include "firmware_model/unit_firmware.h"
#include "hil/recording/recording_format.h"

namespace adahrs::hil {

/// The exponent of each of the nine IMU output slots in `mode` (kRaw: those of kThermal, which
/// shares its layout).
std::array<int, 9> ImuSlotExponents(firmware_model::ImuCompensationMode mode);

/// Sets accel_ticks, gyro_cnt, temp_cnt, mode, comp and comp_flags of `row` from `data`.
void SetPacketColumns(const firmware_model::ImuDataPayload& data, ImuRecordRow& row);
/// Sets the five count columns, mode, alt_ft, cas_kt and comp_flags of `row` from `data`.
void SetPacketColumns(const firmware_model::AdsDataPayload& data, AdsRecordRow& row);

}  // namespace adahrs::hil
