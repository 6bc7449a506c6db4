#include "rig_sim/fixture_orientation.h"

#include <stdexcept>
#include <string>

namespace adahrs::rig_sim {

bool IsValidOrientation(int code) {
  const int axis = code / 10, sense = code % 10;
  return axis >= 1 && axis <= 3 && (sense == 1 || sense == 2);
}

Eigen::Vector3d UpAxis_B(int code) {
  if (!IsValidOrientation(code)) {
    throw std::invalid_argument("orientation code " + std::to_string(code) +
                                " is not one of 11, 12, 21, 22, 31, 32");
  }
  const double sign = code % 10 == 1 ? 1.0 : -1.0;
  return sign * Eigen::Vector3d::Unit(code / 10 - 1);
}

}  // namespace adahrs::rig_sim
