#include "common/imu_layout.h"

#include <stdexcept>
#include <string>

namespace adahrs::common {
namespace {

// Rows are the package axes expressed in B (see the header's table).
Eigen::Matrix3d Rows(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  Eigen::Matrix3d r;
  r.row(0) = x.transpose();
  r.row(1) = y.transpose();
  r.row(2) = x.cross(y).transpose();
  return r;
}

void CheckIndex(int index, const char* what) {
  if (index < 0 || index > 2) {
    throw std::out_of_range(std::string("Im3Geometry: ") + what + " index " +
                            std::to_string(index) + " not in 0..2");
  }
}

}  // namespace

Eigen::Matrix3d NominalR_CB(int chip) {
  CheckIndex(chip, "accelerometer chip");
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                        z = Eigen::Vector3d::UnitZ();
  switch (chip) {
    case 0:
      return Rows(-z, -x);
    case 1:
      return Rows(y, z);
    default:
      return Rows(x, -y);
  }
}

Eigen::Matrix3d NominalR_GB(int gyro) {
  CheckIndex(gyro, "gyro");
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                        z = Eigen::Vector3d::UnitZ();
  // Package z_G along the sensed body axis; x_G, y_G complete a right-handed frame.
  switch (gyro) {
    case 0:
      return Rows(y, z);  // z_G = y × z = +x_B
    case 1:
      return Rows(z, x);  // z_G = z × x = +y_B
    default:
      return Rows(x, y);  // z_G = +z_B
  }
}

}  // namespace adahrs::common
