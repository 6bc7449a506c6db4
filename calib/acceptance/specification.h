// The unit specification as data (reference-method.md "Specification the unit must meet", thesis
// Tables 1-5): tolerances, operating limits, rated temperature and a marginal band per quantity,
// read from a versioned specification file (docs/acceptance.md "Specification file"; shipped:
// calib/specifications/ahr150a-a.json, ahr150a-b.json). Reference() is ahr150a-a.json compiled in
// byte for byte, so its SHA-256 is the shipped file's. A passing point whose |error| exceeds
// (1 - band fraction) x tolerance is MARGINAL. Altitude and airspeed tolerances are linear between
// the stated points (an ASSUMPTION, docs/acceptance.md); outside the operating limits there is no
// tolerance (std::out_of_range).
// Not modelled: heading and attitude tolerances, tolerances that depend on temperature.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
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

inline constexpr const char* kSpecificationFormatName = "adahrs-specification";
inline constexpr int kSpecificationFormatVersion = 1;

/// A specification file that cannot be read or is malformed; what() names the file and JSON path.
class SpecificationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The fraction of each family's tolerance, just below it, in which a passing point is MARGINAL.
struct MarginalBands {
  double acceleration = 0.0;
  double body_rate = 0.0;
  double altitude = 0.0;
  double airspeed = 0.0;
};

/// The thermal acceptance of the reference method (section 4.2.5: the output logged through a
/// thermal ramp; its standard deviation stayed within 0.20 deg/s and 4 mg): per body axis the
/// standard deviation of the error over a thermal_profile step (acceptance_judge.h), against these
/// limits. Optional in a specification file: without it thermal_profile steps are judged per
/// temperature bin only.
struct ThermalStability {
  double accel_std_mg = 4.0;
  double rate_std_dps = 0.20;
  double marginal_band = 0.0;
};

struct Specification {
  std::string name;               ///< "AHR150A-A"
  std::string version;            ///< the specification's own revision, as the file states it
  std::string sha256;             ///< of the file's bytes, 64 lowercase hex digits
  double accel_mg = 1.0;          ///< per axis, any orientation
  double body_rate_dps = 0.015;   ///< per axis
  double rated_rate_dps = 150.0;  ///< operating limit of the body rates
  double rated_accel_g = 10.0;    ///< operating limit of the accelerations (stated, not judged)
  double temp_min_c = -40.0;
  double temp_max_c = 85.0;
  ToleranceTable altitude_ft;  ///< tolerance in ft vs pressure altitude in ft
  ToleranceTable airspeed_kt;  ///< tolerance in kt vs calibrated airspeed in kt
  MarginalBands marginal_band;
  std::optional<ThermalStability> thermal_stability;

  /// The AHR150A -A specification: calib/specifications/ahr150a-a.json as compiled in.
  static Specification Reference();
  /// The band fraction of a family ("acceleration", "body_rate", "altitude", "airspeed", and with
  /// thermal_stability "thermal_acceleration_std", "thermal_body_rate_std").
  double MarginalBandOf(const std::string& family) const;
  /// The identity, tables, scalars and bands as JSON (for acceptance.json and evaluation.json).
  nlohmann::json ToJson() const;
};

/// Parses a specification file's text (`source` names it in messages); sha256 is of `text`.
/// Throws SpecificationError naming the source and the JSON path of a missing key, a wrong type,
/// a value out of range, an unknown key or quantity, or tables that do not enclose their points.
Specification ParseSpecification(const std::string& text, const std::string& source);

/// Reads and parses a specification file (ParseSpecification over the file's bytes).
Specification ReadSpecificationFile(const std::filesystem::path& file);

}  // namespace adahrs::calib
