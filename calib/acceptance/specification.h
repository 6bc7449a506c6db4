// The unit specification as data (reference-method.md "Specification the unit must meet", thesis
// Tables 1-5): the tolerances acceptance and evaluation judge against.
//
//   accelerations      1.0 mg (1 mg = 9.80665e-3 m/s^2, the unit g, not local gravity)
//   body rates         0.015 deg/s
//   altitude           +-15 ft from -1,000 ft to 10,000 ft; +-20 ft at 30,000 ft; +-80 ft at
//                      50,000 ft (operating limits -1,000...50,000 ft)
//   airspeed           +-5 kt at 60 kt; +-2 at 100; +-1 at 300 and 450 (operating 30...450 kt)
//   temperature        -40...+85 degC (every tolerance holds over it)
//
// Interpolation between table points (ASSUMPTION — the specification states only the points):
// the tolerance is linear in the input between neighbouring stated points (altitude between
// 10,000 and 30,000 ft goes 15 -> 20 ft, between 30,000 and 50,000 ft 20 -> 80 ft; airspeed between
// 60 and 100 kt 5 -> 2 kt, 100 -> 300 kt 2 -> 1 kt). Below the first stated airspeed (30...60 kt)
// the 60 kt tolerance is held (ASSUMPTION: the table does not go lower, the operating range does).
// Outside the operating limits there is no tolerance: the lookup throws std::out_of_range.
// The linear rule is the natural reading of a tolerance that widens with altitude as the
// pressure sensitivity falls; a user who reads the table as steps can compare with the
// stated points only (ToleranceTable::points()).
// Not modelled: heading and attitude tolerances (no attitude solution in this product yet),
// tolerances that depend on temperature (the specification states none).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

/// One stated point of a tolerance table.
struct TolerancePoint {
  double input = 0.0;      ///< altitude ft or airspeed kt
  double tolerance = 0.0;  ///< +- the same unit
};

/// A tolerance that varies with its input, piecewise linear between stated points.
class ToleranceTable {
 public:
  /// `points` strictly increasing in input; the tolerance below the first point is held down to
  /// `input_min` (which is <= the first point), the last point must equal `input_max`.
  ToleranceTable(std::string quantity,
                 std::string unit,
                 std::vector<TolerancePoint> points,
                 double input_min,
                 double input_max);

  /// The tolerance at `input` by the rule in the header comment; throws std::out_of_range naming
  /// the quantity and the limits outside [input_min, input_max].
  double At(double input) const;

  const std::string& quantity() const { return quantity_; }
  const std::string& unit() const { return unit_; }
  const std::vector<TolerancePoint>& points() const { return points_; }
  double input_min() const { return input_min_; }
  double input_max() const { return input_max_; }

 private:
  std::string quantity_;
  std::string unit_;
  std::vector<TolerancePoint> points_;
  double input_min_;
  double input_max_;
};

struct Specification {
  double accel_mg = 1.0;          ///< per axis, any orientation
  double body_rate_dps = 0.015;   ///< per axis
  double rated_rate_dps = 150.0;  ///< operating limit of the body rates
  double temp_min_c = -40.0;
  double temp_max_c = 85.0;
  ToleranceTable altitude_ft;  ///< tolerance in ft vs pressure altitude in ft
  ToleranceTable airspeed_kt;  ///< tolerance in kt vs calibrated airspeed in kt

  /// The reference specification (Tables 1-5) with the interpolation rule above.
  static Specification Reference();
  /// The tables and scalars as JSON (for acceptance.json and evaluation.json).
  nlohmann::json ToJson() const;
};

}  // namespace adahrs::calib
