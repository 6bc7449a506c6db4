#include "calib/acceptance/specification.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "common/param_reader.h"
#include "common/printable_text.h"
#include "common/sha256.h"
#include "reference_specification_text.h"

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
  nlohmann::json j = {{"name", name},
                      {"version", version},
                      {"sha256", sha256},
                      {"accel_mg", accel_mg},
                      {"body_rate_dps", body_rate_dps},
                      {"rated_rate_dps", rated_rate_dps},
                      {"rated_accel_g", rated_accel_g},
                      {"temp_min_c", temp_min_c},
                      {"temp_max_c", temp_max_c},
                      {"altitude_ft", TableJson(altitude_ft)},
                      {"airspeed_kt", TableJson(airspeed_kt)},
                      {"marginal_band_fraction",
                       {{"acceleration", marginal_band.acceleration},
                        {"body_rate", marginal_band.body_rate},
                        {"altitude", marginal_band.altitude},
                        {"airspeed", marginal_band.airspeed}}}};
  if (thermal_stability) {
    j["thermal_stability"] = {{"accel_std_mg", thermal_stability->accel_std_mg},
                              {"rate_std_dps", thermal_stability->rate_std_dps},
                              {"marginal_band_fraction", thermal_stability->marginal_band}};
  }
  return j;
}

double Specification::MarginalBandOf(const std::string& family) const {
  if (family == "acceleration") return marginal_band.acceleration;
  if (family == "body_rate") return marginal_band.body_rate;
  if (family == "altitude") return marginal_band.altitude;
  if (family == "airspeed") return marginal_band.airspeed;
  if (thermal_stability &&
      (family == "thermal_acceleration_std" || family == "thermal_body_rate_std")) {
    return thermal_stability->marginal_band;
  }
  throw std::invalid_argument("no marginal band for the quantity family \"" + family + "\"");
}

namespace {

using common::ParamReader;

constexpr const char* kQuantities[] = {
    "acceleration", "body_rate", "altitude", "airspeed", "thermal_stability"};
// Wide enough for any unit's figures, narrow enough to catch a value in the wrong unit.
constexpr double kMaxBandFraction = 0.5;

double Band(const ParamReader& q) {
  return q.Number("marginal_band_fraction", 0.0, kMaxBandFraction, "(fraction of the tolerance)");
}

// A tolerance table: "points_<unit>": [[input, tolerance], ...] strictly increasing in input,
// inside "input_min_<unit>"..."input_max_<unit>", the last point at input_max.
ToleranceTable TableFrom(const ParamReader& q,
                         const nlohmann::json& object,
                         const std::string& quantity,
                         const std::string& unit,
                         double input_lo,
                         double input_hi,
                         double tolerance_max) {
  const std::string key = "points_" + unit;
  const size_t n = q.ArrayLength(key, 1, 64);
  const nlohmann::json& rows = object.at(key);
  std::vector<TolerancePoint> points;
  for (size_t i = 0; i < n; ++i) {
    const std::string where = fmt::format("{}.{}[{}]", q.path(), key, i);
    const nlohmann::json& row = rows[i];
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number()) {
      q.Fail(where, fmt::format("expected [input {}, tolerance {}], two numbers", unit, unit));
    }
    const TolerancePoint point{row[0].get<double>(), row[1].get<double>()};
    if (!(point.input >= input_lo && point.input <= input_hi)) {
      q.Fail(where + "[0]",
             fmt::format("input {} out of range; allowed range [{}, {}] {}",
                         point.input,
                         input_lo,
                         input_hi,
                         unit));
    }
    if (!(point.tolerance > 0.0 && point.tolerance <= tolerance_max)) {
      q.Fail(where + "[1]",
             fmt::format("tolerance {} out of range; allowed range (0, {}] {}",
                         point.tolerance,
                         tolerance_max,
                         unit));
    }
    if (!points.empty() && !(point.input > points.back().input)) {
      q.Fail(where + "[0]", "inputs must increase strictly from point to point");
    }
    points.push_back(point);
  }
  const double min = q.Number("input_min_" + unit, input_lo, input_hi, unit);
  const double max = q.Number("input_max_" + unit, input_lo, input_hi, unit);
  if (min > points.front().input) {
    q.Fail(q.path() + ".input_min_" + unit, "lies above the first point's input");
  }
  if (max != points.back().input) {
    q.Fail(q.path() + ".input_max_" + unit, "must equal the last point's input");
  }
  return ToleranceTable(quantity, unit, std::move(points), min, max);
}

// Refuses a quantity this program does not judge (a typo, or heading before it is judged).
void CheckQuantityNames(const ParamReader& r, const nlohmann::json& quantities) {
  for (const auto& [key, value] : quantities.items()) {
    if (std::find(std::begin(kQuantities), std::end(kQuantities), key) == std::end(kQuantities)) {
      r.Fail(r.path() + "." + key,
             "unknown quantity (known: acceleration, body_rate, altitude, airspeed, "
             "thermal_stability)");
    }
  }
}

void CheckNotes(const ParamReader& r, const nlohmann::json& doc) {
  const size_t n = r.ArrayLength("notes", 0, 256);
  for (size_t i = 0; i < n; ++i) {
    if (!doc["notes"][i].is_string()) r.Fail(fmt::format("$.notes[{}]", i), "expected a string");
  }
}

Specification FromJson(const nlohmann::json& doc, const std::string& source) {
  const ParamReader r(doc, source);
  const std::string format = r.String("format");
  if (format != kSpecificationFormatName) {
    r.Fail("$.format",
           fmt::format("expected \"{}\", got \"{}\"", kSpecificationFormatName, format));
  }
  const int64_t format_version = r.Integer("format_version", 1, 1'000'000);
  if (format_version != kSpecificationFormatVersion) {
    r.Fail("$.format_version",
           fmt::format("{} is not {} (this program reads version {})",
                       format_version,
                       kSpecificationFormatVersion,
                       kSpecificationFormatVersion));
  }
  const std::string name = r.String("name");
  if (name.empty()) r.Fail("$.name", "must not be empty");
  const std::string version = r.String("version");
  if (version.empty()) r.Fail("$.version", "must not be empty");
  (void)r.String("description");
  CheckNotes(r, doc);

  const ParamReader temperature = r.Child("temperature");
  const double temp_min_c = temperature.Number("min_c", -100.0, 200.0, "degC");
  const double temp_max_c = temperature.Number("max_c", temp_min_c, 200.0, "degC");
  temperature.ExpectAllKeysUsed();
  const ParamReader limits = r.Child("operating_limits");
  const double rated_rate_dps = limits.Number("rate_dps", 1.0, 10000.0, "deg/s");
  const double rated_accel_g = limits.Number("accel_g", 1.0, 1000.0, "g");
  limits.ExpectAllKeysUsed();

  const ParamReader quantities = r.Child("quantities");
  CheckQuantityNames(quantities, doc.at("quantities"));
  const nlohmann::json& q_json = doc.at("quantities");
  const ParamReader accel = quantities.Child("acceleration");
  const double accel_mg = accel.Number("tolerance_mg", 1e-6, 1000.0, "mg");
  const double accel_band = Band(accel);
  accel.ExpectAllKeysUsed();
  const ParamReader rate = quantities.Child("body_rate");
  const double body_rate_dps = rate.Number("tolerance_dps", 1e-9, 100.0, "deg/s");
  const double rate_band = Band(rate);
  rate.ExpectAllKeysUsed();
  const ParamReader altitude = quantities.Child("altitude");
  ToleranceTable altitude_ft =
      TableFrom(altitude, q_json.at("altitude"), "altitude", "ft", -2000.0, 100000.0, 10000.0);
  const double altitude_band = Band(altitude);
  altitude.ExpectAllKeysUsed();
  const ParamReader airspeed = quantities.Child("airspeed");
  ToleranceTable airspeed_kt =
      TableFrom(airspeed, q_json.at("airspeed"), "airspeed", "kt", 0.0, 1500.0, 500.0);
  const double airspeed_band = Band(airspeed);
  airspeed.ExpectAllKeysUsed();
  std::optional<ThermalStability> thermal_stability;
  if (quantities.Has("thermal_stability")) {
    const ParamReader thermal = quantities.Child("thermal_stability");
    thermal_stability =
        ThermalStability{.accel_std_mg = thermal.Number("accel_std_mg", 1e-6, 1000.0, "mg"),
                         .rate_std_dps = thermal.Number("rate_std_dps", 1e-9, 100.0, "deg/s"),
                         .marginal_band = Band(thermal)};
    thermal.ExpectAllKeysUsed();
  }
  quantities.ExpectAllKeysUsed();
  r.ExpectAllKeysUsed();

  return Specification{
      .name = name,
      .version = version,
      .sha256 = "",
      .accel_mg = accel_mg,
      .body_rate_dps = body_rate_dps,
      .rated_rate_dps = rated_rate_dps,
      .rated_accel_g = rated_accel_g,
      .temp_min_c = temp_min_c,
      .temp_max_c = temp_max_c,
      .altitude_ft = std::move(altitude_ft),
      .airspeed_kt = std::move(airspeed_kt),
      .marginal_band = {accel_band, rate_band, altitude_band, airspeed_band},
      .thermal_stability = thermal_stability,
  };
}

}  // namespace

Specification ParseSpecification(const std::string& text, const std::string& source) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw SpecificationError(source + ": not valid JSON at byte " + std::to_string(e.byte) + ": " +
                             common::PrintableText(e.what()));
  } catch (const nlohmann::json::exception& e) {
    throw SpecificationError(source + ": not valid JSON: " + common::PrintableText(e.what()));
  }
  try {
    Specification spec = FromJson(doc, source);
    spec.sha256 = common::Sha256Hex(text);
    return spec;
  } catch (const common::ParamError& e) {
    throw SpecificationError(e.what());
  } catch (const std::invalid_argument& e) {  // ToleranceTable's own checks
    throw SpecificationError(source + ": " + e.what());
  }
}

Specification ReadSpecificationFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SpecificationError(file.string() + ": cannot open the specification file");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw SpecificationError(file.string() + ": cannot read the specification file");
  return ParseSpecification(text, file.string());
}

Specification Specification::Reference() {
  static const Specification reference =
      ParseSpecification(kReferenceSpecificationText, kReferenceSpecificationSource);
  return reference;
}

}  // namespace adahrs::calib
