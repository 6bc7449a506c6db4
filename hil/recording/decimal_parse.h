// Decimal cells of a recording parsed exactly as std::from_chars parses them, with fast paths for
// the short cells a recording holds: an integer of at most 18 digits, and a decimal of at most 15
// significant digits without exponent (Clinger's fast path: the digits and the power of ten are
// exact doubles, so one division rounds correctly). Anything else goes to std::from_chars.
#pragma once

#include <charconv>
#include <cstdint>
#include <string_view>

namespace adahrs::hil {

/// An optional '-' and decimal digits, the whole cell; false otherwise or out of range.
inline bool ParseDecimalInteger(std::string_view cell, long long& value) {
  const char* p = cell.data();
  const char* const end = p + cell.size();
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  if (p == end || end - p > 18) {
    const auto [stop, ec] = std::from_chars(cell.data(), end, value);
    return ec == std::errc() && stop == end;
  }
  unsigned long long digits = 0;
  for (; p != end; ++p) {
    const unsigned d = static_cast<unsigned>(*p) - '0';
    if (d > 9) return false;
    digits = digits * 10 + d;
  }
  value = negative ? -static_cast<long long>(digits) : static_cast<long long>(digits);
  return true;
}

/// A number in std::from_chars' general format, the whole cell; false otherwise.
inline bool ParseDecimalReal(std::string_view cell, double& value) {
  static constexpr double kPow10[] = {
      1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const char* p = cell.data();
  const char* const end = p + cell.size();
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  uint64_t digits = 0;
  int count = 0;     // digits taken
  int fraction = 0;  // of them after the point
  bool point = false;
  bool fast = p != end;
  for (; p != end && fast; ++p) {
    const unsigned d = static_cast<unsigned>(*p) - '0';
    if (d <= 9) {
      digits = digits * 10 + d;
      ++count;
      fraction += point ? 1 : 0;
    } else if (*p == '.' && !point) {
      point = true;
    } else {
      fast = false;
    }
  }
  if (fast && count > 0 && count <= 15 && !(point && cell.back() == '.')) {
    const double magnitude = static_cast<double>(digits) / kPow10[fraction];
    value = negative ? -magnitude : magnitude;
    return true;
  }
  const auto [stop, ec] = std::from_chars(cell.data(), end, value);
  return ec == std::errc() && stop == end;
}

}  // namespace adahrs::hil
