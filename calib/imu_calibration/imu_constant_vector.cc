#include "calib/imu_calibration/imu_constant_vector.h"

namespace adahrs::calib {

namespace fm = firmware_model;

Eigen::VectorXd FlattenConstants(const fm::ImuCalibrationConstants& c) {
  Eigen::VectorXd v(kImuFirmwareNumbers);
  int k = 0;
  for (const auto& t : c.thermal) {
    for (double x : t.k) v[k++] = x;
  }
  for (const auto& a : c.accel) {
    v[k++] = a.offset_duty;
    v[k++] = a.scale_duty_per_g;
  }
  for (const auto& g : c.gyro) {
    v[k++] = g.null_cnt;
    for (double x : g.l) v[k++] = x;
  }
  for (const auto& row : c.ca_mps2_per_g) {
    for (double x : row) v[k++] = x;
  }
  for (const auto& row : c.cg) {
    for (double x : row) v[k++] = x;
  }
  const fm::ImuScaleTemperature& st = c.scale_temperature;
  for (const auto& f : st.scale) {
    for (double x : f) v[k++] = st.active ? x : 0.0;
  }
  for (double q : st.accel_quadratic_per_g) v[k++] = st.active ? q : 0.0;
  for (const auto& row : st.gs_dps_per_mps2) {
    for (double x : row) v[k++] = st.active ? x : 0.0;
  }
  return v;
}

fm::ImuCalibrationConstants UnflattenConstants(const Eigen::VectorXd& v,
                                               const fm::ImuCalibrationConstants& like) {
  fm::ImuCalibrationConstants c = like;
  int k = 0;
  for (auto& t : c.thermal) {
    for (double& x : t.k) x = v[k++];
  }
  for (auto& a : c.accel) {
    a.offset_duty = v[k++];
    a.scale_duty_per_g = v[k++];
  }
  for (auto& g : c.gyro) {
    g.null_cnt = v[k++];
    for (double& x : g.l) x = v[k++];
  }
  for (auto& row : c.ca_mps2_per_g) {
    for (double& x : row) x = v[k++];
  }
  for (auto& row : c.cg) {
    for (double& x : row) x = v[k++];
  }
  fm::ImuScaleTemperature& st = c.scale_temperature;
  for (auto& f : st.scale) {
    for (double& x : f) x = v[k++];
  }
  for (double& q : st.accel_quadratic_per_g) q = v[k++];
  for (auto& row : st.gs_dps_per_mps2) {
    for (double& x : row) x = v[k++];
  }
  return c;
}

std::vector<std::string> ConstantNames() {
  std::vector<std::string> names;
  for (int ch = 0; ch < 9; ++ch) {
    for (int i = 0; i <= kMaxThermalOrder; ++i) {
      names.push_back("thermal[" + std::to_string(ch) + "].k[" + std::to_string(i) + "]");
    }
  }
  for (int ch = 0; ch < 6; ++ch) {
    names.push_back("accel[" + std::to_string(ch) + "].offset_duty");
    names.push_back("accel[" + std::to_string(ch) + "].scale_duty_per_g");
  }
  for (int g = 0; g < 3; ++g) {
    names.push_back("gyro[" + std::to_string(g) + "].null_cnt");
    for (int i = 0; i < 4; ++i) {
      names.push_back("gyro[" + std::to_string(g) + "].l[" + std::to_string(i) + "]");
    }
  }
  for (const char* m : {"ca_mps2_per_g", "cg"}) {
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) {
        names.push_back(std::string(m) + "[" + std::to_string(r) + "][" + std::to_string(k) + "]");
      }
    }
  }
  for (int ch = 0; ch < 9; ++ch) {
    for (int i = 0; i < 4; ++i) {
      names.push_back("scale_temperature.scale[" + std::to_string(ch) + "][" + std::to_string(i) +
                      "]");
    }
  }
  for (int a = 0; a < 3; ++a) {
    names.push_back("scale_temperature.accel_quadratic_per_g[" + std::to_string(a) + "]");
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      names.push_back("scale_temperature.gs_dps_per_mps2[" + std::to_string(r) + "][" +
                      std::to_string(k) + "]");
    }
  }
  return names;
}

}  // namespace adahrs::calib
