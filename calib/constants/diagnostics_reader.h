// The reader both fit-diagnostics sections of constants.json share (imu_fit_diagnostics.h,
// ads_fit_diagnostics.h): every value read by key with its JSON path, an unknown key refused, a
// number written null (NaN when written) read back as NaN. Errors are ConstantsFileError.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/constants/constants_file.h"
#include "common/imu_layout.h"

namespace adahrs::calib {

/// One JSON object of a diagnostics section; the keys read are recorded so that ExpectAllKeysUsed
/// can refuse the others.
class DiagnosticsReader {
 public:
  DiagnosticsReader(const nlohmann::json& j, const std::string& source, std::string path)
      : j_(&j), source_(&source), path_(std::move(path)) {
    if (!j.is_object()) Fail(path_, "expected an object");
  }

  [[noreturn]] void Fail(const std::string& where, const std::string& message) const {
    throw ConstantsFileError(*source_ + ": " + where + ": " + message);
  }
  std::string PathOf(const std::string& key) const { return path_ + "." + key; }
  bool Has(const std::string& key) const { return j_->contains(key); }

  const nlohmann::json& Require(const std::string& key) const {
    const auto it = j_->find(key);
    if (it == j_->end()) Fail(PathOf(key), "missing key");
    used_.insert(key);
    return *it;
  }
  double NumberAt(const nlohmann::json& v, const std::string& where) const {
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number()) Fail(where, "expected a number or null");
    return v.get<double>();
  }
  double Number(const std::string& key) const { return NumberAt(Require(key), PathOf(key)); }
  int64_t Integer(const std::string& key) const {
    const nlohmann::json& v = Require(key);
    if (!v.is_number_integer()) Fail(PathOf(key), "expected an integer");
    return v.get<int64_t>();
  }
  int Int(const std::string& key) const {
    const int64_t x = Integer(key);
    if (x < std::numeric_limits<int>::min() || x > std::numeric_limits<int>::max())
      Fail(PathOf(key), "out of range");
    return static_cast<int>(x);
  }
  bool Flag(const std::string& key) const {
    const nlohmann::json& v = Require(key);
    if (!v.is_boolean()) Fail(PathOf(key), "expected true or false");
    return v.get<bool>();
  }
  std::string String(const std::string& key) const {
    const nlohmann::json& v = Require(key);
    if (!v.is_string()) Fail(PathOf(key), "expected a string");
    return v.get<std::string>();
  }
  const nlohmann::json& Array(const std::string& key) const {
    const nlohmann::json& v = Require(key);
    if (!v.is_array()) Fail(PathOf(key), "expected an array");
    return v;
  }
  std::vector<double> Numbers(const nlohmann::json& array, const std::string& where) const {
    if (!array.is_array()) Fail(where, "expected an array");
    std::vector<double> out;
    for (size_t i = 0; i < array.size(); ++i)
      out.push_back(NumberAt(array[i], where + "[" + std::to_string(i) + "]"));
    return out;
  }
  std::vector<double> Numbers(const std::string& key) const {
    return Numbers(Require(key), PathOf(key));
  }
  std::vector<std::string> Strings(const std::string& key) const {
    const nlohmann::json& array = Array(key);
    std::vector<std::string> out;
    for (size_t i = 0; i < array.size(); ++i) {
      if (!array[i].is_string())
        Fail(PathOf(key) + "[" + std::to_string(i) + "]", "expected a string");
      out.push_back(array[i].get<std::string>());
    }
    return out;
  }
  DiagnosticsReader Child(const std::string& key) const {
    return DiagnosticsReader(Require(key), *source_, PathOf(key));
  }
  DiagnosticsReader Element(const nlohmann::json& array, size_t i, const std::string& key) const {
    return DiagnosticsReader(array[i], *source_, PathOf(key) + "[" + std::to_string(i) + "]");
  }
  // Every key of the object, in the file's order.
  std::vector<std::string> Keys() const {
    std::vector<std::string> keys;
    for (const auto& [key, value] : j_->items()) keys.push_back(key);
    return keys;
  }
  // The keys of a per-channel map, each one of the nine channels.
  std::vector<std::string> ChannelKeys() const {
    std::vector<std::string> keys;
    for (const auto& [key, value] : j_->items()) {
      if (std::find(common::kImuChannelNames.begin(), common::kImuChannelNames.end(), key) ==
          common::kImuChannelNames.end()) {
        Fail(PathOf(key), "not a channel (az1, ax1, ay1, az2, ax2, ay2, gx, gy, gz)");
      }
      keys.push_back(key);
    }
    return keys;
  }
  void ExpectAllKeysUsed() const {
    for (const auto& [key, value] : j_->items()) {
      if (!used_.contains(key)) Fail(PathOf(key), "unknown key");
    }
  }

 private:
  const nlohmann::json* j_;
  const std::string* source_;
  std::string path_;
  mutable std::set<std::string> used_;
};

}  // namespace adahrs::calib
