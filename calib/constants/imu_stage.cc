#include "calib/constants/imu_stage.h"

namespace adahrs::calib {

namespace fm = firmware_model;

std::string_view ImuStageName(ImuStage stage) {
  switch (stage) {
    case ImuStage::kThermal:
      return "thermal";
    case ImuStage::kSensor:
      return "sensor";
    case ImuStage::kCrossAxis:
      return "cross_axis";
  }
  return "?";
}

std::optional<ImuStage> ParseImuStage(std::string_view name) {
  for (ImuStage s : kImuStages) {
    if (ImuStageName(s) == name) return s;
  }
  return std::nullopt;
}

std::vector<ImuStage> StagesThrough(ImuStage stage) {
  std::vector<ImuStage> stages;
  for (ImuStage s : kImuStages) {
    stages.push_back(s);
    if (s == stage) break;
  }
  return stages;
}

fm::ImuCompensationMode ModeAfter(ImuStage stage) {
  switch (stage) {
    case ImuStage::kThermal:
      return fm::ImuCompensationMode::kThermal;
    case ImuStage::kSensor:
      return fm::ImuCompensationMode::kSensorCalibrated;
    case ImuStage::kCrossAxis:
      return fm::ImuCompensationMode::kFullyCalibrated;
  }
  return fm::ImuCompensationMode::kRaw;
}

}  // namespace adahrs::calib
