#include "sensor_sim/im3_geometry.h"

#include "common/imu_layout.h"
#include "common/random.h"
#include "common/units.h"

namespace adahrs::sensor_sim {
namespace {

Eigen::Matrix3d SmallRotation(const Eigen::Vector3d& theta_deg) {
  const double angle_rad = common::DegToRad(theta_deg.norm());
  if (angle_rad == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle_rad, theta_deg.normalized()).toRotationMatrix();
}

nlohmann::json VectorJson(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

Eigen::Matrix3d Im3Geometry::R_CB(int chip) const {
  const Eigen::Matrix3d nominal = common::NominalR_CB(chip);
  return misalignment ? Eigen::Matrix3d(nominal * SmallRotation(accel_misalignment_deg[chip]))
                      : nominal;
}

Eigen::Matrix3d Im3Geometry::R_GB(int gyro) const {
  const Eigen::Matrix3d nominal = common::NominalR_GB(gyro);
  return misalignment ? Eigen::Matrix3d(nominal * SmallRotation(gyro_misalignment_deg[gyro]))
                      : nominal;
}

Im3Geometry Im3Geometry::Draw(uint64_t seed) {
  common::Rng rng(seed);
  Im3Geometry g;
  for (auto* set : {&g.accel_misalignment_deg, &g.gyro_misalignment_deg}) {
    for (Eigen::Vector3d& theta : *set) {
      for (int k = 0; k < 3; ++k) theta[k] = rng.Tolerance(0.0, 1.0);
    }
  }
  return g;
}

nlohmann::json Im3Geometry::ToJson() const {
  nlohmann::json accel = nlohmann::json::array(), gyro = nlohmann::json::array();
  for (const auto& v : accel_misalignment_deg) accel.push_back(VectorJson(v));
  for (const auto& v : gyro_misalignment_deg) gyro.push_back(VectorJson(v));
  return {{"accel_misalignment_deg", accel},
          {"gyro_misalignment_deg", gyro},
          {"effects", {{"misalignment", misalignment}}}};
}

Im3Geometry Im3Geometry::FromJson(const common::ParamReader& reader) {
  Im3Geometry g;
  std::array<std::array<double, 3>, 3> accel{}, gyro{};
  reader.NumberMatrix("accel_misalignment_deg", -5.0, 5.0, "deg", accel);
  reader.NumberMatrix("gyro_misalignment_deg", -5.0, 5.0, "deg", gyro);
  for (int i = 0; i < 3; ++i) {
    g.accel_misalignment_deg[i] = Eigen::Vector3d(accel[i][0], accel[i][1], accel[i][2]);
    g.gyro_misalignment_deg[i] = Eigen::Vector3d(gyro[i][0], gyro[i][1], gyro[i][2]);
  }
  const common::ParamReader effects = reader.Child("effects");
  g.misalignment = effects.Flag("misalignment");
  effects.ExpectAllKeysUsed();
  reader.ExpectAllKeysUsed();
  return g;
}

}  // namespace adahrs::sensor_sim
