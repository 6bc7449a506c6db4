// The checks on an external strategy's reply (docs/strategies-external.md "The checks"): a valid
// reply of a plausible constants set is taken as written; each malformed or out-of-range reply is
// refused with its cause and JSON path.
#include "calib/imu_calibration/external_reply.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/imu_layout.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

// A set the firmware can hold: ADXL210E-like scales, an ADXRS150-like gyro scale, 1 g = 9.8 m/s^2.
firmware_model::ImuCalibrationConstants Plausible() {
  firmware_model::ImuCalibrationConstants c;
  for (int ch = 0; ch < 9; ++ch) {
    c.thermal[ch] = {common::kImuChannels[ch].thermometer, {1e-3, -1e-7, 2e-12, 0.0}, 26000, 40000};
  }
  for (int ch = 0; ch < 6; ++ch) c.accel[ch] = {0.001 * ch, common::kImuChannels[ch].sign * 0.04};
  for (int g = 0; g < 3; ++g) c.gyro[g] = {100.0 * g, {0.1, 4.7e-5, 1e-15, -1e-20}};
  for (int i = 0; i < 3; ++i) {
    c.ca_mps2_per_g[i][i] = 9.8;
    c.cg[i][i] = 1.0;
  }
  c.ca_mps2_per_g[0][1] = -0.06;
  c.cg[2][0] = -0.01;
  return c;
}

json Reply(const json& constants = firmware_model::ToJson(Plausible())) {
  return {{"protocol", "adahrs-strategy-reply"},
          {"protocol_version", 1},
          {"serial", "IMU-0001"},
          {"constants", constants},
          {"log", {"fitted"}}};
}

std::string Refusal(const std::string& bytes, int format = 2) {
  try {
    CheckExternalReply(bytes, "IMU-0001", format);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "accepted";
}

std::string Refusal(const json& reply, int format = 2) { return Refusal(reply.dump(), format); }

TEST(ExternalReply, TakesAValidReplyAsWritten) {
  const CheckedReply r = CheckExternalReply(Reply().dump(), "IMU-0001", 2);
  EXPECT_EQ(firmware_model::ToJson(r.constants), firmware_model::ToJson(Plausible()));
  EXPECT_EQ(r.log, std::vector<std::string>{"fitted"});
  EXPECT_TRUE(r.standard_errors.at("accel").at(0).at("offset_duty").is_null());
}

TEST(ExternalReply, RefusesWhatIsNotOneJsonObject) {
  EXPECT_THAT(Refusal(std::string("")), HasSubstr("is not one JSON object"));
  const std::string half = Reply().dump().substr(0, 100);
  EXPECT_THAT(Refusal(half), HasSubstr("is not one JSON object"));
  EXPECT_THAT(Refusal(half), HasSubstr("it began: \"{\"constants\":{"));
  EXPECT_THAT(Refusal(Reply().dump() + "\n{}"), HasSubstr("is not one JSON object"));
  EXPECT_THAT(Refusal(std::string("[1, 2]")), HasSubstr("not an object"));
}

TEST(ExternalReply, RefusesANumberBeyondADouble) {
  std::string bytes = Reply().dump();
  const std::string nine_eight = "9.8";
  bytes.replace(bytes.find(nine_eight), nine_eight.size(), "3.08e6486");
  EXPECT_THAT(Refusal(bytes), HasSubstr("is not one JSON object"));
}

TEST(ExternalReply, RefusesNaNWrittenAsPythonWritesIt) {
  std::string bytes = Reply().dump();
  const std::string nine_eight = "9.8";
  bytes.replace(bytes.find(nine_eight), nine_eight.size(), "NaN");
  EXPECT_THAT(Refusal(bytes), HasSubstr("is not one JSON object"));
}

TEST(ExternalReply, RefusesANullOrMissingConstantWithItsPath) {
  json reply = Reply();
  reply["constants"]["gyro"][1]["l"][2] = nullptr;
  EXPECT_THAT(Refusal(reply), HasSubstr("$.constants.gyro[1].l[2]"));
  reply = Reply();
  reply["constants"].erase("cg");
  EXPECT_THAT(Refusal(reply), HasSubstr("$.constants.cg: missing"));
}

TEST(ExternalReply, RefusesTheWrongProtocolSerialOrKeys) {
  json reply = Reply();
  reply["protocol_version"] = 2;
  EXPECT_THAT(Refusal(reply), HasSubstr("$.protocol_version: expected 1, got 2"));
  reply = Reply();
  reply["serial"] = "IMU-0002";
  EXPECT_THAT(Refusal(reply), HasSubstr("$.serial: the request was for IMU-0001"));
  reply = Reply();
  reply["constant"] = 1;
  EXPECT_THAT(Refusal(reply), HasSubstr("$.constant: unexpected key"));
  reply = Reply();
  reply.erase("protocol");
  EXPECT_THAT(Refusal(reply), HasSubstr("$.protocol: missing"));
  reply = Reply();
  reply["log"] = {"ok", 3};
  EXPECT_THAT(Refusal(reply), HasSubstr("$.log[1]: expected a string"));
}

TEST(ExternalReply, RefusesConstantsTheFirmwareCannotHold) {
  firmware_model::ImuCalibrationConstants c = Plausible();
  c.thermal[2].k[0] = 5.0;  // a drift of 5 duty: the thermal block holds less than 1
  EXPECT_THAT(Refusal(Reply(firmware_model::ToJson(c))), HasSubstr("not representable"));
  c = Plausible();
  c.thermal[4].temp_sensor = 0;
  EXPECT_THAT(Refusal(Reply(firmware_model::ToJson(c))),
              HasSubstr("$.constants.thermal[4].temp_sensor: 0, the firmware compensates ax2 "
                        "with thermometer 2"));
}

TEST(ExternalReply, HoldsFormatThreeTermsExactlyWhenAsked) {
  EXPECT_THAT(Refusal(Reply(), 3), HasSubstr("scale_temperature: missing"));
  firmware_model::ImuCalibrationConstants c = Plausible();
  c.scale_temperature.active = true;
  for (auto& s : c.scale_temperature.scale) s = {1.0, 0.0, 0.0, 0.0};
  EXPECT_THAT(Refusal(Reply(firmware_model::ToJson(c)), 2),
              HasSubstr("scale_temperature: present"));
  EXPECT_EQ(Refusal(Reply(firmware_model::ToJson(c)), 3), "accepted");
}

TEST(ExternalReply, RefusesANegativeStandardError) {
  json reply = Reply();
  const CheckedReply valid = CheckExternalReply(Reply().dump(), "IMU-0001", 2);
  reply["standard_errors"] = valid.standard_errors;
  reply["standard_errors"]["accel"][0]["offset_duty"] = -1e-6;
  EXPECT_THAT(Refusal(reply), HasSubstr("$.standard_errors"));
}

}  // namespace
}  // namespace adahrs::calib
