#include "hil/codecs/atl_command_table.h"
#include "adahrs_build_paths.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/param_reader.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

const std::string kDefaultTable = ADAHRS_SOURCE_DIR "/rig_sim/data/atl_commands.json";

nlohmann::json DefaultJson() { return common::ParamReader::LoadFile(kDefaultTable); }

// Expects FromJson to refuse `table` with a message holding every one of `parts`.
void ExpectRefused(const nlohmann::json& table, const std::vector<std::string>& parts) {
  try {
    AtlCommandTable::FromJson(table, "edited.json");
    FAIL() << "accepted";
  } catch (const common::ParamError& e) {
    for (const std::string& part : parts) EXPECT_THAT(e.what(), HasSubstr(part));
  }
}

TEST(AtlCommandTable, DefaultTableHoldsTheMnemonicsOfProtocolsSection12) {
  const AtlCommandTable table = AtlCommandTable::Load(kDefaultTable);
  // protocols.md §1.2: the fourteen mnemonics seen in third-party clients, plus our two queries.
  for (const char* m : {"HOM",
                        "STO",
                        "JOG",
                        "ACL",
                        "SRV",
                        "CLU",
                        "CAL",
                        "REX",
                        "PPO",
                        "SGO",
                        "AMP",
                        "FRQ",
                        "CYC",
                        "P",
                        "RAT",
                        "STA"}) {
    EXPECT_NE(table.Find(m), nullptr) << m;
  }
  EXPECT_EQ(table.commands().size(), 16u);
  const AtlCommandSpec* jog = table.Find("JOG");
  ASSERT_NE(jog, nullptr);
  EXPECT_EQ(jog->confidence, "DRV");
  EXPECT_EQ(jog->operation, "rate");
  ASSERT_TRUE(jog->action.has_value());
  // The package's comment: integer, bi-directional 360 deg/s.
  EXPECT_EQ(jog->action->argument, AtlArgument::kInteger);
  EXPECT_EQ(jog->action->min, -360.0);
  EXPECT_EQ(jog->action->max, 360.0);
  EXPECT_TRUE(jog->query.has_value());
  // Invented mnemonics are marked UNKNOWN, and have no action form.
  EXPECT_EQ(table.Find("RAT")->confidence, "UNKNOWN");
  EXPECT_FALSE(table.Find("RAT")->action.has_value());
  EXPECT_EQ(table.FindOperation("move")->mnemonic, "P");
  // Framing of the only observed client (DRV): "\r\n>\r\n".
  EXPECT_EQ(table.framing().line_end, "\r\n");
  EXPECT_EQ(table.framing().prompt, ">");
  EXPECT_EQ(table.framing().confidence, "DRV");
  EXPECT_EQ(table.errors().confidence, "UNKNOWN");
  EXPECT_EQ(table.Find("XYZ"), nullptr);
}

TEST(AtlCommandTable, AMisspeltKeyIsRefusedWithFileAndPath) {
  nlohmann::json t = DefaultJson();
  t["commands"][0]["action"]["maximum"] = t["commands"][0]["action"]["max"];
  t["commands"][0]["action"].erase("max");
  ExpectRefused(t, {"edited.json", "$.commands[0].action.max", "missing key"});
  t = DefaultJson();
  t["commands"][2]["units"] = "deg";
  ExpectRefused(t, {"$.commands[2].units", "unknown key"});
}

TEST(AtlCommandTable, BadEntriesAreRefusedNamingTheRuleBroken) {
  nlohmann::json t = DefaultJson();
  t["commands"][0]["action"]["argument"] = "float";
  ExpectRefused(t,
                {"$.commands[0].action.argument", "\"float\" is not one of none, integer, real"});
  t = DefaultJson();
  t["commands"][0]["action"]["min"] = 400;
  ExpectRefused(t, {"$.commands[0].action.max", "max is below min"});
  t = DefaultJson();
  t["commands"][0]["action"]["max"] = 360.5;
  ExpectRefused(t, {"$.commands[0].action.min", "integer argument must be integers"});
  t = DefaultJson();
  t["commands"][1]["mnemonic"] = "JOG";
  ExpectRefused(t, {"$.commands[1].mnemonic", "duplicate mnemonic JOG"});
  t = DefaultJson();
  t["commands"][1]["mnemonic"] = "sto";
  ExpectRefused(t, {"$.commands[1].mnemonic", "upper-case letters only"});
  t = DefaultJson();
  t["commands"][0]["query"]["reply"] = "RATE";
  ExpectRefused(t, {"$.commands[0].query.reply", "has no {value}"});
  t = DefaultJson();
  t["commands"][0]["confidence"] = "SURE";
  ExpectRefused(t, {"$.commands[0].confidence", "not one of DOC, DRV, INF, UNKNOWN"});
  t = DefaultJson();
  t["commands"][1].erase("action");
  ExpectRefused(t, {"$.commands[1]", "neither an action nor a query form"});
  t = DefaultJson();
  t["commands"] = nlohmann::json::array();
  ExpectRefused(t, {"$.commands", "non-empty array"});
  t = DefaultJson();
  t["format"] = "atl-2";
  ExpectRefused(t, {"$.format"});
}

TEST(AtlCommandTable, AMissingFileIsNamed) {
  try {
    AtlCommandTable::Load("/nonexistent/atl.json");
    FAIL() << "accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/atl.json"));
  }
}

}  // namespace
}  // namespace adahrs::hil
