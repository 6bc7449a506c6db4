// A simulated IMU's raw frame (sensor_sim::ImuRawFrame: the T1/T2 captures, summed gyro counts and
// TEMP counts the dsPIC acquires) in the firmware's layout (firmware_model::ImuRawFrame), as the
// compensator and the calibration observations take it. Same values, no unit change.
// Left out: the rig's unit device builds its packet payload directly (rig_sim cannot use calib).
#pragma once

#include "firmware_model/unit_firmware.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {

firmware_model::ImuRawFrame ToFirmwareRawFrame(const sensor_sim::ImuRawFrame& frame);

}  // namespace adahrs::proving
