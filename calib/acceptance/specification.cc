#include "calib/acceptance/specification.h"

#include <sstream>
#include <stdexcept>

namespace adahrs::calib {

ToleranceTable::ToleranceTable(std::string quantity,
                               std::string unit,
                               std::vector<TolerancePoint> points,
                               double input_min,
                               double input_max)
    : quantity_(std::move(quantity)),
      unit_(std::move(unit)),
      points_(std::move(points)),
      input_min_(input_min),
      input_max_(input_max) {
  if (points_.empty()) throw std::invalid_argument(quantity_ + " tolerance table: no points");
  for (size_t i = 1; i < points_.size(); ++i) {
    if (!(points_[i].input > points_[i - 1].input)) {
      throw std::invalid_argument(quantity_ + " tolerance table: inputs not strictly increasing");
    }
  }
  if (input_min_ > points_.front().input || points_.back().input != input_max_) {
    throw std::invalid_argument(quantity_ + " tolerance table: limits do not enclose the points");
  }
}

double ToleranceTable::At(double input) const {
  if (!(input >= input_min_ && input <= input_max_)) {
    std::ostringstream message;
    message << quantity_ << " " << input << " " << unit_ << " is outside the operating limits "
            << input_min_ << "..." << input_max_ << " " << unit_ << ": no tolerance is specified";
    throw std::out_of_range(message.str());
  }
  if (input <= points_.front().input) return points_.front().tolerance;
  for (size_t i = 1; i < points_.size(); ++i) {
    if (input <= points_[i].input) {
      const TolerancePoint& a = points_[i - 1];
      const TolerancePoint& b = points_[i];
      const double f = (input - a.input) / (b.input - a.input);
      return a.tolerance + f * (b.tolerance - a.tolerance);
    }
  }
  return points_.back().tolerance;
}

Specification Specification::Reference() {
  return Specification{
      .accel_mg = 1.0,
      .body_rate_dps = 0.015,
      .rated_rate_dps = 150.0,
      .temp_min_c = -40.0,
      .temp_max_c = 85.0,
      .altitude_ft =
          ToleranceTable("altitude",
                         "ft",
                         {{-1000.0, 15.0}, {10000.0, 15.0}, {30000.0, 20.0}, {50000.0, 80.0}},
                         -1000.0,
                         50000.0),
      .airspeed_kt = ToleranceTable(
          "airspeed", "kt", {{60.0, 5.0}, {100.0, 2.0}, {300.0, 1.0}, {450.0, 1.0}}, 30.0, 450.0),
  };
}

namespace {
nlohmann::json TableJson(const ToleranceTable& t) {
  nlohmann::json points = nlohmann::json::array();
  for (const TolerancePoint& p : t.points()) points.push_back({p.input, p.tolerance});
  return {
      {"unit", t.unit()},
      {"points", points},
      {"input_min", t.input_min()},
      {"input_max", t.input_max()},
      {"interpolation", "linear between stated points (assumption); first point held below it"}};
}
}  // namespace

nlohmann::json Specification::ToJson() const {
  return {{"accel_mg", accel_mg},
          {"body_rate_dps", body_rate_dps},
          {"rated_rate_dps", rated_rate_dps},
          {"temp_min_c", temp_min_c},
          {"temp_max_c", temp_max_c},
          {"altitude_ft", TableJson(altitude_ft)},
          {"airspeed_kt", TableJson(airspeed_kt)}};
}

}  // namespace adahrs::calib
