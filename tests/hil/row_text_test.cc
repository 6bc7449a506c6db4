#include "hil/recording/row_text.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

std::string Printf(const char* format, double value, int digits) {
  char text[512];
  std::snprintf(text, sizeof text, format, digits, value);
  return text;
}

std::string Fixed(double value, int digits) {
  std::vector<char> buffer;
  RowText row(buffer, 0);
  row.Fixed(value, digits);
  return std::string(row.data(), row.size());
}

// The recording's text must stay what printf's "%.Nf" wrote (golden hashes of recordings depend
// on it), including the rounding of exact binary ties to even and of -0.
TEST(RowText, FixedIsPrintfText) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 12);
  for (int i = 0; i < 200000; ++i) {
    const double v = mantissa(random) * std::pow(10.0, exponent(random));
    for (int digits : {2, 3, 4}) ASSERT_EQ(Fixed(v, digits), Printf("%.*f", v, digits)) << v;
  }
  for (double v : {0.125, 0.375, -0.125, 2.5, 0.00005, 1e300, -1e-300, -0.0, 0.0, 12345.67895}) {
    for (int digits : {0, 2, 3, 4}) EXPECT_EQ(Fixed(v, digits), Printf("%.*f", v, digits)) << v;
  }
}

TEST(RowText, ShortestReadsBackExactly) {
  std::mt19937_64 random(9);
  std::uniform_int_distribution<int32_t> word(std::numeric_limits<int32_t>::min());
  for (int i = 0; i < 100000; ++i) {
    const double v = std::ldexp(static_cast<double>(word(random)), -31 + i % 40);
    std::vector<char> buffer;
    RowText row(buffer, 0);
    row.Shortest(v);
    const std::string text(row.data(), row.size());
    ASSERT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
  }
}

TEST(RowText, IntegersAndTextAreAsPrintf) {
  std::vector<char> buffer;
  RowText row(buffer, 8);
  row.Text("IMU-0001");
  row.Comma();
  row.Integer(-2147483647 - 1);
  row.Comma();
  row.Integer(4294967295u);
  row.Char('\n');
  char expected[64];
  std::snprintf(expected, sizeof expected, "%s,%d,%u\n", "IMU-0001", -2147483647 - 1, 4294967295u);
  EXPECT_EQ(std::string(row.data(), row.size()), expected);
}

}  // namespace
}  // namespace adahrs::hil
