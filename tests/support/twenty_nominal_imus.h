// The IMU tests' 20 nominal units and what they check the Cramér-Rao bound with.
// ForEachNominalImuBatch: IMU-0001...IMU-0020 (seeds 501...520, ModelProfile::kNominal, then the
// truth variant), in five batches of four; each batch's thermal and sensor calibration runs are
// made by the recording maker (300 packets per acquisition, thermal profile compressed 60x) under
// `base`, handed to `on_batch`, and removed.
// GyroErrorOverCrb: the RMS over the gyro nulls and gyro thermal coefficients of (error / CRB
// standard error), the error against the projection of the true unit (evaluation.json
// parameters). About 1 for an honest bound.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "proving/evaluation/imu_evaluation.h"
#include "sensor_sim/imu_unit.h"
#include "tests/support/imu_recording_maker.h"

namespace adahrs::calib::testing {

using NominalImuBatch = std::function<void(const std::vector<sensor_sim::ImuUnitParams>& params,
                                           const std::filesystem::path& thermal_run,
                                           const std::filesystem::path& sensor_run)>;

inline void ForEachNominalImuBatch(const std::filesystem::path& base,
                                   double g_local_mps2,
                                   sensor_sim::TruthVariant variant,
                                   const NominalImuBatch& on_batch) {
  MakerOptions maker_options;
  maker_options.thermal_speedup = 60.0;
  for (int batch = 0; batch < 5; ++batch) {
    std::vector<sensor_sim::ImuUnitParams> params;
    for (int i = 0; i < 4; ++i) {
      const int n = 4 * batch + i + 1;
      params.push_back(sensor_sim::ImuUnitParams::Draw(
          "IMU-" + std::string(n < 10 ? "000" : "00") + std::to_string(n),
          500 + n,
          sensor_sim::ModelProfile::kNominal));
      params.back().ApplyVariant(variant);
    }
    ImuRecordingMaker maker(params, g_local_mps2, 900 + batch, maker_options);
    const auto thermal = base / ("thermal" + std::to_string(batch));
    const auto sensor = base / ("sensor" + std::to_string(batch));
    maker.Run(ShippedSequence("imu_thermal_calibration_full", 300), thermal);
    maker.Run(ShippedSequence("imu_sensor_calibration", 300), sensor);
    on_batch(params, thermal, sensor);
    std::filesystem::remove_all(thermal);
    std::filesystem::remove_all(sensor);
  }
}

inline double GyroErrorOverCrb(const proving::ImuEvaluation& e) {
  double sum = 0.0;
  int n = 0;
  for (const auto& p : e.report["parameters"]) {
    const std::string name = p["name"];
    const bool gyro = name.rfind("thermal[6]", 0) == 0 || name.rfind("thermal[7]", 0) == 0 ||
                      name.rfind("thermal[8]", 0) == 0 ||
                      name.find("null_cnt") != std::string::npos;
    if (!gyro || !p.contains("error_over_crb")) continue;
    sum += std::pow(p["error_over_crb"].get<double>(), 2);
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace adahrs::calib::testing
