#include "common/param_reader.h"
#include "tests/support/error_text.h"

#include <filesystem>
#include <fstream>
#include <functional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::common {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& f) {
  return test_support::ErrorText<ParamError>(f);
}

TEST(ParamReader, ReadsValuesInRange) {
  const auto j = nlohmann::json::parse(R"({"a": {"gain_mv_per_dps": 12.5, "n": 16, "on": true}})");
  ParamReader r(j, "unit.json");
  ParamReader a = r.Child("a");
  EXPECT_DOUBLE_EQ(a.Number("gain_mv_per_dps", 10, 15, "mV/(deg/s)"), 12.5);
  EXPECT_EQ(a.Integer("n", 1, 64), 16);
  EXPECT_TRUE(a.Flag("on"));
  a.ExpectAllKeysUsed();
  r.ExpectAllKeysUsed();
}

TEST(ParamReader, MissingKeyNamesFileAndPath) {
  const auto j = nlohmann::json::parse(R"({"a": {}})");
  ParamReader r(j, "unit.json");
  EXPECT_THAT(
      ErrorOf([&] { r.Child("a").Number("gain_mv_per_dps", 10, 15, "mV"); }),
      AllOf(HasSubstr("unit.json"), HasSubstr("$.a.gain_mv_per_dps"), HasSubstr("missing")));
}

TEST(ParamReader, OutOfRangeNamesAllowedRange) {
  const auto j = nlohmann::json::parse(R"({"t2_ms": 20})");
  ParamReader r(j, "chip.json");
  EXPECT_THAT(ErrorOf([&] { r.Number("t2_ms", 0.5, 10, "ms"); }),
              AllOf(HasSubstr("$.t2_ms"), HasSubstr("out of range"), HasSubstr("[0.5, 10] ms")));
}

TEST(ParamReader, NanAsStringIsRefused) {
  const auto j = nlohmann::json::parse(R"({"x_v": "NaN"})");
  ParamReader r(j, "f.json");
  EXPECT_THAT(ErrorOf([&] { r.Number("x_v", 0, 1, "V"); }),
              AllOf(HasSubstr("$.x_v"), HasSubstr("expected a number")));
}

TEST(ParamReader, QuotedKeysAndValuesHaveTheirControlBytesEscaped) {
  nlohmann::json j;
  j["x_v"] = "1\x1b[2J\r";
  j["y\x1b]0;title\x07"] = 1;
  ParamReader r(j, "f.json");
  EXPECT_THAT(ErrorOf([&] { r.Number("x_v", 0, 1, "V"); }), HasSubstr("\"1\\x1B[2J\\r\""));
  EXPECT_THAT(ErrorOf([&] { r.ExpectAllKeysUsed(); }), HasSubstr("y\\x1B]0;title\\x07"));
}

TEST(ParamReader, InvalidUtf8InAFileIsEscapedInTheParseError) {
  const auto path = std::filesystem::temp_directory_path() / "adahrs_param_reader_binary.json";
  std::ofstream(path, std::ios::binary) << "{\"a\": \xff\xfe\r}";
  const std::string error = ErrorOf([&] { ParamReader::LoadFile(path.string()); });
  std::filesystem::remove(path);
  EXPECT_THAT(error, HasSubstr("not valid JSON"));
  EXPECT_EQ(error.find_first_of("\xff\xfe\r"), std::string::npos) << error;
}

TEST(ParamReader, WrongUnitSuffixIsAnUnknownKey) {
  const auto j = nlohmann::json::parse(R"({"offset_v": 0.1, "offset_mv": 100})");
  ParamReader r(j, "f.json");
  r.Number("offset_v", -1, 1, "V");
  EXPECT_THAT(ErrorOf([&] { r.ExpectAllKeysUsed(); }),
              AllOf(HasSubstr("$.offset_mv"), HasSubstr("unknown key")));
}

TEST(ParamReader, WrongTypeIsRefused) {
  const auto j = nlohmann::json::parse(R"({"n": 1.5, "on": 1})");
  ParamReader r(j, "f.json");
  EXPECT_THAT(ErrorOf([&] { r.Integer("n", 0, 4); }), HasSubstr("expected an integer"));
  EXPECT_THAT(ErrorOf([&] { r.Flag("on"); }), HasSubstr("expected true or false"));
}

// A number beyond double's range is a parse failure of the file, named as such (it escaped as
// a bare "[json.exception.out_of_range.406]").
TEST(ParamReader, NumberBeyondDoubleRangeNamesTheFile) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "adahrs_param_reader_1e400.json").string();
  std::ofstream(path) << R"({"x": 1e400})";
  EXPECT_THAT(ErrorOf([&] { ParamReader::LoadFile(path); }),
              AllOf(HasSubstr(path + ": not valid JSON"), HasSubstr("1e400")));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace adahrs::common
