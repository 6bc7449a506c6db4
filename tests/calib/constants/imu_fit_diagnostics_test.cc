// ImuFitDiagnostics::FromJson on hand-written diagnostics sections: a wrong type, an unknown key,
// a key that is not a channel and a bad covariance entry are refused naming the source and the
// JSON path; null (how a NaN is written) reads back as NaN. The read-back of a real fit's
// constants.json is in imu_reference_fit_test.cc.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/constants/constants_file.h"
#include "calib/constants/imu_fit_diagnostics.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

std::string Refusal(const json& j) {
  try {
    ImuFitDiagnostics::FromJson(j, "unit.json");
  } catch (const ConstantsFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted " << j.dump();
  return "";
}

json Joint(const json& channels, const json& crb) {
  return {{"channels", channels},
          {"observations", 3},
          {"crb_parameters", {"a"}},
          {"crb_covariance", crb},
          {"firmware_cannot_hold", ""}};
}

TEST(ImuFitDiagnostics, BadInputIsRefusedNamingTheJsonPath) {
  EXPECT_THAT(Refusal(json::array()), HasSubstr("unit.json: $.diagnostics: expected an object"));
  EXPECT_THAT(Refusal({{"local_gravity_mps2", "9.8"}}),
              HasSubstr("unit.json: $.diagnostics.local_gravity_mps2: expected a number"));
  EXPECT_THAT(Refusal({{"local_gravity_mpss2", 9.8}}),
              HasSubstr("$.diagnostics.local_gravity_mpss2: unknown key"));
  EXPECT_THAT(Refusal(Joint({{"gq", json::object()}}, {{0.0}})),
              HasSubstr("$.diagnostics.channels.gq: not a channel"));
  EXPECT_THAT(Refusal(Joint(json::object(), {{0.0}, {1.0, "x"}})),
              HasSubstr("$.diagnostics.crb_covariance[1][1]: expected a number or null"));
  EXPECT_THAT(Refusal(Joint({{"gx", {{"thermal_order", 2}}}}, {{0.0}})),
              HasSubstr("$.diagnostics.channels.gx.model_error_rms: missing key"));
}

TEST(ImuFitDiagnostics, NullReadsBackAsNan) {
  const ImuFitDiagnostics d =
      ImuFitDiagnostics::FromJson(Joint(json::object(), {{nullptr}}), "unit.json");
  ASSERT_TRUE(d.joint.has_value());
  ASSERT_EQ(d.joint->crb_covariance.size(), 1u);
  EXPECT_TRUE(std::isnan(d.joint->crb_covariance[0][0]));
  EXPECT_FALSE(d.reference.has_value());
  EXPECT_FALSE(d.local_gravity_mps2.has_value());
}

}  // namespace
}  // namespace adahrs::calib
