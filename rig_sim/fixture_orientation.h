// The fixture's orientation codes (reference-method.md §3, Table 9): two digits, the first the
// body axis made vertical (1 = x_B, 2 = y_B, 3 = z_B), the second its sense (1 = pointing up,
// 2 = pointing down, i.e. the unit rotated 180°). With the axis pointing up the unit at rest
// senses a specific force of +1 local g along it, which reproduces the reference's channel signs
// (az1 sees −1 g in orientation 31, az2 +1 g). On the rate table the vertical axis is the table
// axis, so a table rate ω (positive counter-clockwise seen from above) appears as +ω about the
// up-pointing body axis.
// Left out: fixture levelling error and table wobble (rig parameters, added by the rig world).
#pragma once

#include <Eigen/Dense>

namespace adahrs::rig_sim {

/// True for 11, 12, 21, 22, 31, 32.
bool IsValidOrientation(int code);

/// The unit vector of the body frame that points up in `code`, expressed in B. Throws
/// std::invalid_argument naming the code when it is not valid.
Eigen::Vector3d UpAxis_B(int code);

}  // namespace adahrs::rig_sim
