// Strict reader for parameter files (JSON). Every value is read by name, with its allowed range
// and unit stated by the caller; a missing key, a wrong type, a NaN, a value out of range or an
// unknown key (which is how a wrong unit shows: `offset_mv` where `offset_v` is expected) throws
// ParamError naming the source file, the JSON path and the allowed range. Nothing is defaulted.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace adahrs::common {

/// Thrown for any invalid parameter input; what() names source, JSON path and the rule broken.
class ParamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads one JSON object and records which of its keys were read, so that `ExpectAllKeysUsed()`
/// can refuse keys nobody asked for. `Child()` gives a reader of a nested object with its own
/// record.
class ParamReader {
 public:
  /// `source` names where the JSON came from (a file path, or a description) for messages.
  ParamReader(const nlohmann::json& object, std::string source, std::string path = "$");

  /// Loads and parses a file; parse errors name the file and byte offset.
  static nlohmann::json LoadFile(const std::string& file_path);

  /// A finite number in [min, max]; `unit` is printed in messages.
  double Number(std::string_view key, double min, double max, std::string_view unit) const;
  /// An integer in [min, max].
  int64_t Integer(std::string_view key, int64_t min, int64_t max) const;
  /// A boolean.
  bool Flag(std::string_view key) const;
  /// A string.
  std::string String(std::string_view key) const;
  /// A nested object.
  ParamReader Child(std::string_view key) const;
  /// The length of the array held under `key`, which must hold between `min` and `max` items.
  size_t ArrayLength(std::string_view key, size_t min, size_t max) const;
  /// Element `index` of an array of exactly `count` objects held under `key`.
  ParamReader Element(std::string_view key, size_t index, size_t count) const;
  /// Whether a key is present (for documented optional blocks only).
  bool Has(std::string_view key) const;
  /// A fixed-length array of finite numbers in [min, max].
  template <typename Out>
  void NumberArray(
      std::string_view key, double min, double max, std::string_view unit, Out& out) const {
    const nlohmann::json& array = Require(key);
    const std::string where = PathOf(key);
    if (!array.is_array() || array.size() != std::size(out)) {
      Fail(where, "expected an array of " + std::to_string(std::size(out)) + " numbers");
    }
    for (size_t i = 0; i < std::size(out); ++i) {
      out[i] = CheckNumber(array[i], where + "[" + std::to_string(i) + "]", min, max, unit);
    }
  }

  /// A fixed-size array of fixed-length arrays (rows) of finite numbers in [min, max].
  template <typename Row, size_t kRows>
  void NumberMatrix(std::string_view key,
                    double min,
                    double max,
                    std::string_view unit,
                    std::array<Row, kRows>& out) const {
    const nlohmann::json& rows = Require(key);
    const std::string where = PathOf(key);
    if (!rows.is_array() || rows.size() != kRows) {
      Fail(where, "expected an array of " + std::to_string(kRows) + " rows");
    }
    for (size_t r = 0; r < kRows; ++r) {
      const std::string row_where = where + "[" + std::to_string(r) + "]";
      if (!rows[r].is_array() || rows[r].size() != std::size(out[r])) {
        Fail(row_where, "expected an array of " + std::to_string(std::size(out[r])) + " numbers");
      }
      for (size_t c = 0; c < std::size(out[r]); ++c) {
        out[r][c] =
            CheckNumber(rows[r][c], row_where + "[" + std::to_string(c) + "]", min, max, unit);
      }
    }
  }

  /// Throws if the object holds a key that no accessor asked for (a typo or a wrong unit suffix).
  void ExpectAllKeysUsed() const;

  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }

  /// Throws ParamError with the source and `where` in front of `message`.
  [[noreturn]] void Fail(const std::string& where, const std::string& message) const;

 private:
  const nlohmann::json& Require(std::string_view key) const;
  std::string PathOf(std::string_view key) const;
  double CheckNumber(const nlohmann::json& value,
                     const std::string& where,
                     double min,
                     double max,
                     std::string_view unit) const;

  const nlohmann::json* object_;
  std::string source_;
  std::string path_;
  std::shared_ptr<std::set<std::string>> used_;
};

}  // namespace adahrs::common
