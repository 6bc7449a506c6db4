// The recording's fast decimal parsers against std::from_chars, the definition they follow: the
// same verdict and the same bits on edge cases and on random cells of a recording's alphabet.
#include "hil/recording/decimal_parse.h"

#include <charconv>
#include <cstring>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

void ExpectLikeFromChars(const std::string& cell) {
  long long fast_integer = 0;
  long long library_integer = 0;
  const auto [int_end, int_ec] =
      std::from_chars(cell.data(), cell.data() + cell.size(), library_integer);
  const bool library_int_ok = int_ec == std::errc() && int_end == cell.data() + cell.size();
  ASSERT_EQ(ParseDecimalInteger(cell, fast_integer), library_int_ok) << "'" << cell << "'";
  if (library_int_ok) {
    EXPECT_EQ(fast_integer, library_integer) << "'" << cell << "'";
  }

  double fast_real = 0.0;
  double library_real = 0.0;
  const auto [real_end, real_ec] =
      std::from_chars(cell.data(), cell.data() + cell.size(), library_real);
  const bool library_real_ok = real_ec == std::errc() && real_end == cell.data() + cell.size();
  ASSERT_EQ(ParseDecimalReal(cell, fast_real), library_real_ok) << "'" << cell << "'";
  if (library_real_ok) {
    uint64_t fast_bits = 0;
    uint64_t library_bits = 0;
    std::memcpy(&fast_bits, &fast_real, sizeof fast_bits);
    std::memcpy(&library_bits, &library_real, sizeof library_bits);
    EXPECT_EQ(fast_bits, library_bits) << "'" << cell << "'";
  }
}

TEST(DecimalParse, EdgeCellsParseAsFromCharsParsesThem) {
  for (const char* cell : {"",
                           "-",
                           "+1",
                           "0",
                           "-0",
                           "007",
                           "5.",
                           ".5",
                           "-.5",
                           ".",
                           "-.",
                           "1.2.3",
                           "1e5",
                           "1E-3",
                           "nan",
                           "inf",
                           " 1",
                           "1 ",
                           "12a",
                           "0.1",
                           "0.3",
                           "-0.000",
                           "123456789012345",
                           "1234567890123456",
                           "9223372036854775807",
                           "-9223372036854775808",
                           "9223372036854775808",
                           "999999999999999999",
                           "-999999999999999999",
                           "1.00000000000001",
                           "0.000000000000001",
                           "8.10000000000000",
                           "43210.98765",
                           "1234567.891234"}) {
    ExpectLikeFromChars(cell);
  }
}

TEST(DecimalParse, RandomCellsParseAsFromCharsParsesThem) {
  std::mt19937_64 rng(20261128);
  const std::string alphabet = "0123456789.-e+ x";
  std::uniform_int_distribution<int> length(0, 22);
  std::uniform_int_distribution<int> pick_digit(0, 9);
  std::uniform_int_distribution<size_t> pick_any(0, alphabet.size() - 1);
  std::bernoulli_distribution mostly_number(0.85);
  for (int i = 0; i < 200000; ++i) {
    std::string cell;
    const int n = length(rng);
    const bool number = mostly_number(rng);
    for (int k = 0; k < n; ++k) {
      cell += number ? static_cast<char>('0' + pick_digit(rng)) : alphabet[pick_any(rng)];
    }
    if (number && n > 2 && (rng() & 1)) cell[static_cast<size_t>(rng() % n)] = '.';
    if (number && (rng() & 3) == 0) cell = "-" + cell;
    ExpectLikeFromChars(cell);
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace adahrs::hil
