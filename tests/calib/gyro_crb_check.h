// What the IMU tests check the Cramér-Rao bound with: the RMS over the gyro nulls and gyro
// thermal coefficients of (error / CRB standard error), the error against the projection of the
// true unit (evaluation.json parameters). About 1 for an honest bound.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "calib/evaluation/imu_evaluation.h"

namespace adahrs::calib::testing {

inline double GyroErrorOverCrb(const ImuEvaluation& e) {
  double sum = 0.0;
  int n = 0;
  for (const auto& p : e.report["parameters"]) {
    const std::string name = p["name"];
    const bool gyro = name.rfind("thermal[6]", 0) == 0 || name.rfind("thermal[7]", 0) == 0 ||
                      name.rfind("thermal[8]", 0) == 0 || name.find("null_cnt") != std::string::npos;
    if (!gyro || !p.contains("error_over_crb")) continue;
    sum += std::pow(p["error_over_crb"].get<double>(), 2);
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace adahrs::calib::testing
