#include "common/param_reader.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/printable_text.h"

namespace adahrs::common {

ParamReader::ParamReader(const nlohmann::json& object, std::string source, std::string path)
    : object_(&object),
      source_(std::move(source)),
      path_(std::move(path)),
      used_(std::make_shared<std::set<std::string>>()) {
  if (!object.is_object()) Fail(path_, "expected a JSON object");
}

nlohmann::json ParamReader::LoadFile(const std::string& file_path) {
  std::ifstream in(file_path);
  if (!in) throw ParamError(file_path + ": cannot open for reading");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw ParamError(file_path + ": not valid JSON at byte " + std::to_string(e.byte) + ": " +
                     PrintableText(e.what()));
  } catch (const nlohmann::json::exception& e) {  // a number beyond double's range (1e400)
    throw ParamError(file_path + ": not valid JSON: " + PrintableText(e.what()));
  }
}

void ParamReader::Fail(const std::string& where, const std::string& message) const {
  // `where` holds the file's own keys and `message` may quote its values.
  throw ParamError(source_ + ": " + PrintableText(where) + ": " + PrintableText(message));
}

std::string ParamReader::PathOf(std::string_view key) const {
  return path_ + "." + std::string(key);
}

bool ParamReader::Has(std::string_view key) const { return object_->contains(std::string(key)); }

const nlohmann::json& ParamReader::Require(std::string_view key) const {
  const std::string name(key);
  auto it = object_->find(name);
  if (it == object_->end()) Fail(PathOf(key), "missing key");
  used_->insert(name);
  return *it;
}

double ParamReader::CheckNumber(const nlohmann::json& value,
                                const std::string& where,
                                double min,
                                double max,
                                std::string_view unit) const {
  std::ostringstream range;
  range << "allowed range [" << min << ", " << max << "] " << unit;
  if (value.is_string()) {
    // JSON has no NaN; a string "nan"/"inf" is how such values usually arrive.
    Fail(where,
         "expected a number, got the string \"" + value.get<std::string>() + "\"; " + range.str());
  }
  if (!value.is_number()) Fail(where, "expected a number; " + range.str());
  const double x = value.get<double>();
  if (!std::isfinite(x)) Fail(where, "not a finite number; " + range.str());
  if (x < min || x > max) {
    std::ostringstream got;
    got << "value " << x << " out of range; " << range.str();
    Fail(where, got.str());
  }
  return x;
}

double ParamReader::Number(std::string_view key,
                           double min,
                           double max,
                           std::string_view unit) const {
  return CheckNumber(Require(key), PathOf(key), min, max, unit);
}

int64_t ParamReader::Integer(std::string_view key, int64_t min, int64_t max) const {
  const nlohmann::json& value = Require(key);
  if (!value.is_number_integer()) {
    Fail(PathOf(key),
         "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  const int64_t x = value.get<int64_t>();
  if (x < min || x > max) {
    Fail(PathOf(key),
         "value " + std::to_string(x) + " out of range; allowed range [" + std::to_string(min) +
             ", " + std::to_string(max) + "]");
  }
  return x;
}

bool ParamReader::Flag(std::string_view key) const {
  const nlohmann::json& value = Require(key);
  if (!value.is_boolean()) Fail(PathOf(key), "expected true or false");
  return value.get<bool>();
}

std::string ParamReader::String(std::string_view key) const {
  const nlohmann::json& value = Require(key);
  if (!value.is_string()) Fail(PathOf(key), "expected a string");
  return value.get<std::string>();
}

ParamReader ParamReader::Child(std::string_view key) const {
  return ParamReader(Require(key), source_, PathOf(key));
}

size_t ParamReader::ArrayLength(std::string_view key, size_t min, size_t max) const {
  const nlohmann::json& array = Require(key);
  if (!array.is_array() || array.size() < min || array.size() > max) {
    Fail(PathOf(key),
         "expected an array of " + std::to_string(min) + " to " + std::to_string(max) + " items");
  }
  return array.size();
}

ParamReader ParamReader::Element(std::string_view key, size_t index, size_t count) const {
  const nlohmann::json& array = Require(key);
  if (!array.is_array() || array.size() != count) {
    Fail(PathOf(key), "expected an array of " + std::to_string(count) + " objects");
  }
  return ParamReader(array[index], source_, PathOf(key) + "[" + std::to_string(index) + "]");
}

void ParamReader::ExpectAllKeysUsed() const {
  for (auto it = object_->begin(); it != object_->end(); ++it) {
    if (!used_->count(it.key())) {
      Fail(PathOf(it.key()),
           "unknown key (misspelt, or a unit suffix other than the one expected)");
    }
  }
}

}  // namespace adahrs::common
