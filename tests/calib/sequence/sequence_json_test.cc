#include "calib/sequence/sequence_json.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/calib/sequence/sequence_test_util.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::Joined;
using ::testing::SizeIs;
using testing::TempFile;

// One step of every kind and every profile step type, with explicit and assigned TAGs.
Sequence EveryKind() {
  Sequence s;
  s.name = "every kind";
  s.description = "round-trip fixture";
  s.unit_kind = UnitKind::kImu;
  s.steps.push_back({7, PromptStep{"Mount the batch"}});
  s.steps.push_back({std::nullopt, AccelStep{21, 1000}});
  s.steps.push_back({std::nullopt, GyroStep{31, 500, -150.0, 150.0, 50.0, 100.0}});
  s.steps.push_back({200, TargetTemperatureStep{-20.5, 0.25, 1800.0}});
  s.steps.push_back({std::nullopt, CrossAxisStep{1000, 150.0, 100.0}});
  s.steps.push_back({std::nullopt,
                     ThermalProfileStep{"IMU 1",
                                        {F4RampTime{-20.0, 3600.0},
                                         F4RampRate{65.0, 1.5},
                                         F4Soak{600.0},
                                         F4Jump{1, 2},
                                         F4End{F4EndAction::kIdle, 23.5}}}});
  s.steps.push_back({std::nullopt, AltitudeStep{-1000.0, 3000.0}});
  s.steps.push_back({std::nullopt, AirspeedStep{60.0, 100.0}});
  s.steps.push_back({std::nullopt, LogStep{200, std::nullopt}});
  s.steps.push_back({std::nullopt, LogStep{std::nullopt, 12.5}});
  return s;
}

TEST(SequenceJson, SaveThenLoadIsTheIdentity) {
  const Sequence original = EveryKind();
  const TempFile file("round_trip.json", "");
  SaveSequence(original, file.path());
  const ParsedSequence loaded = ParseSequenceFile(file.path());
  EXPECT_THAT(loaded.problems, SizeIs(0)) << Joined(loaded.problems, file.path());
  EXPECT_EQ(loaded.sequence, original);
}

TEST(SequenceJson, SavedFormHasDocumentedKeys) {
  const nlohmann::ordered_json j = SequenceToJson(EveryKind());
  EXPECT_EQ(j["format_version"], 1);
  EXPECT_EQ(j["unit_kind"], "imu");
  EXPECT_EQ(j["steps"][0]["tag"], 7);
  EXPECT_FALSE(j["steps"][1].contains("tag"));  // assigned TAGs are not written
  EXPECT_EQ(j["steps"][2]["kind"], "gyro");
  EXPECT_EQ(j["steps"][2]["rate_increment_dps"], 50.0);
  EXPECT_EQ(j["steps"][5]["profile_steps"][3]["type"], "jump");
  EXPECT_EQ(j["steps"][5]["profile_steps"][4]["action"], "idle");
  EXPECT_EQ(j["steps"][5]["profile_steps"][4]["idle_c"], 23.5);
}

TEST(SequenceJson, EveryStructuralProblemIsReportedWithPath) {
  // Three bad steps and a bad top-level key: all four problems, not only the first.
  const auto doc = nlohmann::json::parse(R"({
    "format_version": 1, "name": "bad", "description": "", "unit_kind": "imu", "colour": "red",
    "steps": [
      {"kind": "accel", "orientation": 11, "packets": 10},
      {"kind": "accel", "orientation": 11, "packets": 10, "rate_dps": 3},
      {"kind": "gyro", "orientation": 11, "packets": 10, "rate_min_dps": -150,
       "rate_max_dps": 150, "table_accel_dps2": 100},
      {"kind": "spin"},
      {"kind": "log", "packets": 10, "duration_s": 3}
    ]})");
  const ParsedSequence parsed = ParseSequence(doc, "bad.json");
  const std::string text = Joined(parsed.problems, "bad.json");
  EXPECT_THAT(parsed.problems, SizeIs(5)) << text;
  EXPECT_THAT(text,
              AllOf(HasSubstr("bad.json: $.colour: unknown key"),
                    HasSubstr("bad.json: $.steps[1].rate_dps: unknown key"),
                    HasSubstr("bad.json: $.steps[2].rate_increment_dps: missing key"),
                    HasSubstr("$.steps[3].kind: unknown step kind \"spin\""),
                    HasSubstr("$.steps[4]: a log step takes exactly one of packets")));
  // The good step is kept, with its index in the file.
  ASSERT_THAT(parsed.sequence.steps, SizeIs(1));
  EXPECT_EQ(parsed.file_step_index[0], 0u);
}

TEST(SequenceJson, ProfileStepProblemsNameTheProfileStep) {
  const auto doc = nlohmann::json::parse(R"({
    "format_version": 1, "name": "p", "description": "", "unit_kind": "imu",
    "steps": [{"kind": "thermal_profile", "profile_name": "P", "profile_steps": [
      {"type": "ramp_rate", "target_c": 30, "rate_c_per_min": 1},
      {"type": "ramp_rate", "target_c": 30, "rate_c_per_hour": 60},
      {"type": "loop", "to_step": 1},
      {"type": "end", "action": "explode"}]}]})");
  const std::string text = Joined(ParseSequence(doc, "p.json").problems, "p.json");
  EXPECT_THAT(text,
              AllOf(HasSubstr("$.steps[0].profile_steps[1].rate_c_per_min: missing key"),
                    HasSubstr("$.steps[0].profile_steps[2].type: unknown profile step "
                              "type \"loop\""),
                    HasSubstr("$.steps[0].profile_steps[3].action: unknown end action")));
}

TEST(SequenceJson, WrongFormatVersionAndNotJsonAreRefused) {
  const auto doc = nlohmann::json::parse(
      R"({"format_version": 2, "name": "v", "description": "", "unit_kind": "imu", "steps": []})");
  EXPECT_THAT(Joined(ParseSequence(doc, "v.json").problems, "v.json"),
              HasSubstr("$.format_version: value 2 out of range; allowed range [1, 1]"));
  const TempFile file("broken.json", "{\"name\": ");
  const ParsedSequence parsed = ParseSequenceFile(file.path());
  ASSERT_THAT(parsed.problems, SizeIs(1));
  EXPECT_THAT(parsed.problems[0].rule, HasSubstr("not valid JSON"));
}

TEST(SequenceJson, SequenceFromJsonThrowsWithEveryProblem) {
  const auto doc = nlohmann::json::parse(R"({"name": 3, "description": "", "unit_kind": "car",
                                              "steps": []})");
  try {
    SequenceFromJson(doc, "t.json");
    FAIL() << "no exception";
  } catch (const SequenceError& e) {
    EXPECT_THAT(e.problems(), SizeIs(3));  // format_version missing, name type, unit_kind
    EXPECT_THAT(std::string(e.what()),
                AllOf(HasSubstr("t.json: sequence refused, 3 problems"),
                      HasSubstr("t.json: $.format_version: missing key"),
                      HasSubstr("t.json: $.name: expected a string"),
                      HasSubstr("t.json: $.unit_kind: unknown unit kind \"car\"")));
  }
}

}  // namespace
}  // namespace adahrs::calib
