// The specification tables (reference-method.md, thesis Tables 1-5) and the documented
// interpolation rule: stated points exactly, linear between them, held below 60 kt, refused
// outside the operating limits. The shipped files: -A is the compiled-in reference byte for byte,
// -B differs from it only by Table 4's -B operating limits; a malformed file is refused with the
// file and the JSON path.
#include "calib/acceptance/specification.h"
#include "calib/acceptance/ads_tolerance.h"
#include "common/sha256.h"

#include <unistd.h>

#include <fstream>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adahrs_build_paths.h"

namespace adahrs::calib {
namespace {

const std::filesystem::path kSpecDir =
    std::filesystem::path(ADAHRS_SOURCE_DIR) / "calib" / "specifications";

std::string FileText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Specification, StatedPointsAreTheReferenceTables) {
  const Specification s = Specification::Reference();
  EXPECT_EQ(s.accel_mg, 1.0);
  EXPECT_EQ(s.body_rate_dps, 0.015);
  EXPECT_EQ(s.temp_min_c, -40.0);
  EXPECT_EQ(s.temp_max_c, 85.0);
  EXPECT_EQ(s.altitude_ft.At(-1000.0), 15.0);
  EXPECT_EQ(s.altitude_ft.At(0.0), 15.0);
  EXPECT_EQ(s.altitude_ft.At(10000.0), 15.0);
  EXPECT_EQ(s.altitude_ft.At(30000.0), 20.0);
  EXPECT_EQ(s.altitude_ft.At(50000.0), 80.0);
  EXPECT_EQ(s.airspeed_kt.At(60.0), 5.0);
  EXPECT_EQ(s.airspeed_kt.At(100.0), 2.0);
  EXPECT_EQ(s.airspeed_kt.At(300.0), 1.0);
  EXPECT_EQ(s.airspeed_kt.At(450.0), 1.0);
}

TEST(Specification, LinearBetweenPointsHeldBelowTheFirstAirspeed) {
  const Specification s = Specification::Reference();
  EXPECT_DOUBLE_EQ(s.altitude_ft.At(20000.0), 17.5);  // midway 15 -> 20
  EXPECT_DOUBLE_EQ(s.altitude_ft.At(40000.0), 50.0);  // midway 20 -> 80
  EXPECT_DOUBLE_EQ(s.airspeed_kt.At(80.0), 3.5);      // midway 5 -> 2
  EXPECT_DOUBLE_EQ(s.airspeed_kt.At(200.0), 1.5);     // midway 2 -> 1
  EXPECT_EQ(s.airspeed_kt.At(30.0), 5.0);
}

TEST(Specification, OutsideTheOperatingLimitsThereIsNoTolerance) {
  const Specification s = Specification::Reference();
  try {
    s.altitude_ft.At(51000.0);
    FAIL();
  } catch (const std::out_of_range& e) {
    EXPECT_THAT(e.what(),
                ::testing::HasSubstr("altitude 51000 ft is outside the operating limits"));
  }
  EXPECT_THROW(s.airspeed_kt.At(20.0), std::out_of_range);
  EXPECT_THROW(s.altitude_ft.At(-1500.0), std::out_of_range);
}

TEST(Specification, JsonCarriesTheTablesAndTheRule) {
  const nlohmann::json j = Specification::Reference().ToJson();
  EXPECT_EQ(j["altitude_ft"]["points"].size(), 4u);
  EXPECT_EQ(j["airspeed_kt"]["points"][1][1], 2.0);
  EXPECT_THAT(j["altitude_ft"]["interpolation"].get<std::string>(),
              ::testing::HasSubstr("assumption"));
}

// The ADS evaluation keeps its own copy of the tolerance points (with extra report points); both
// copies must give the same tolerance everywhere in the operating limits.
TEST(Specification, AdsEvaluationTolerancesMatchTheSpecification) {
  const Specification s = Specification::Reference();
  for (double alt_ft = -1000.0; alt_ft <= 50000.0; alt_ft += 250.0) {
    EXPECT_DOUBLE_EQ(AltitudeToleranceFt(alt_ft), s.altitude_ft.At(alt_ft)) << alt_ft << " ft";
  }
  for (double cas_kt = 30.0; cas_kt <= 450.0; cas_kt += 2.5) {
    EXPECT_DOUBLE_EQ(AirspeedToleranceKt(cas_kt), s.airspeed_kt.At(cas_kt)) << cas_kt << " kt";
  }
}

TEST(Specification, ShippedAFileIsTheCompiledInReference) {
  const Specification file = ReadSpecificationFile(kSpecDir / "ahr150a-a.json");
  const Specification reference = Specification::Reference();
  EXPECT_EQ(file.ToJson(), reference.ToJson());
  EXPECT_EQ(reference.name, "AHR150A-A");
  EXPECT_EQ(reference.sha256, common::Sha256Hex(FileText(kSpecDir / "ahr150a-a.json")));
  // Table 4, -A model.
  EXPECT_EQ(reference.rated_rate_dps, 150.0);
  EXPECT_EQ(reference.rated_accel_g, 10.0);
}

// Table 4: -B is rated +-300 deg/s and +-18 g; Tables 1-3 and 5 state one figure for both models.
TEST(Specification, ShippedBFileDiffersFromAByTable4Only) {
  const Specification a = Specification::Reference();
  const Specification b = ReadSpecificationFile(kSpecDir / "ahr150a-b.json");
  EXPECT_EQ(b.name, "AHR150A-B");
  EXPECT_EQ(b.rated_rate_dps, 300.0);
  EXPECT_EQ(b.rated_accel_g, 18.0);
  EXPECT_NE(b.sha256, a.sha256);
  nlohmann::json ja = a.ToJson();
  nlohmann::json jb = b.ToJson();
  for (const char* key : {"name", "sha256", "rated_rate_dps", "rated_accel_g"}) {
    ja.erase(key);
    jb.erase(key);
  }
  EXPECT_EQ(ja, jb);
}

class MalformedSpecification : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = std::filesystem::temp_directory_path() /
            ("adahrs_spec_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json");
    doc_ = nlohmann::json::parse(FileText(kSpecDir / "ahr150a-a.json"));
  }
  void TearDown() override { std::filesystem::remove(file_); }

  // The message reading the edited document gives.
  std::string Refusal() {
    std::ofstream(file_) << doc_.dump(2);
    try {
      ReadSpecificationFile(file_);
    } catch (const SpecificationError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(file_.string()));
      return e.what();
    }
    return "(accepted)";
  }

  std::filesystem::path file_;
  nlohmann::json doc_;
};

TEST_F(MalformedSpecification, MissingFieldIsRefusedWithItsPath) {
  doc_["quantities"]["body_rate"].erase("tolerance_dps");
  EXPECT_THAT(Refusal(),
              ::testing::AllOf(::testing::HasSubstr("$.quantities.body_rate.tolerance_dps"),
                               ::testing::HasSubstr("missing key")));
}

TEST_F(MalformedSpecification, WrongTypeIsRefusedWithItsPath) {
  doc_["quantities"]["acceleration"]["tolerance_mg"] = "1.0";
  EXPECT_THAT(Refusal(),
              ::testing::AllOf(::testing::HasSubstr("$.quantities.acceleration.tolerance_mg"),
                               ::testing::HasSubstr("expected a number")));
  doc_ = nlohmann::json::parse(FileText(kSpecDir / "ahr150a-a.json"));
  doc_["quantities"]["altitude"]["points_ft"][2] = {30000.0, "20"};
  EXPECT_THAT(Refusal(), ::testing::HasSubstr("$.quantities.altitude.points_ft[2]"));
}

TEST_F(MalformedSpecification, UnknownQuantityIsRefusedWithItsPath) {
  doc_["quantities"]["heading"] = {{"tolerance_deg", 0.1}, {"marginal_band_fraction", 0.1}};
  EXPECT_THAT(Refusal(),
              ::testing::AllOf(::testing::HasSubstr("$.quantities.heading"),
                               ::testing::HasSubstr("unknown quantity")));
}

TEST_F(MalformedSpecification, WrongUnitSuffixAndBadTablesAreRefused) {
  doc_["operating_limits"]["rate_rps"] = 2.6;  // a unit this file does not use
  EXPECT_THAT(Refusal(), ::testing::HasSubstr("rate_rps"));
  doc_ = nlohmann::json::parse(FileText(kSpecDir / "ahr150a-a.json"));
  doc_["quantities"]["airspeed"]["points_kt"][1][0] = 50.0;  // 60, 50: not increasing
  EXPECT_THAT(Refusal(),
              ::testing::AllOf(::testing::HasSubstr("$.quantities.airspeed.points_kt[1][0]"),
                               ::testing::HasSubstr("increase strictly")));
  doc_ = nlohmann::json::parse(FileText(kSpecDir / "ahr150a-a.json"));
  doc_["quantities"]["airspeed"]["marginal_band_fraction"] = 1.5;
  EXPECT_THAT(Refusal(), ::testing::HasSubstr("$.quantities.airspeed.marginal_band_fraction"));
  doc_ = nlohmann::json::parse(FileText(kSpecDir / "ahr150a-a.json"));
  doc_["format_version"] = 2;
  EXPECT_THAT(Refusal(), ::testing::HasSubstr("$.format_version"));
}

}  // namespace
}  // namespace adahrs::calib
