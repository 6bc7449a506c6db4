#include "hil/codecs/atl_codec.h"
#include "adahrs_build_paths.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

const AtlCommandTable& Table() {
  static const AtlCommandTable table =
      AtlCommandTable::Load(ADAHRS_SOURCE_DIR "/rig_sim/data/atl_commands.json");
  return table;
}

AtlParsed Parse(const std::string& text) { return ParseAtlLine(Table(), AtlLine{text, false}); }

std::vector<AtlLine> Frame(const std::string& bytes, size_t max_chars = 64) {
  AtlLineFramer framer(max_chars);
  std::vector<AtlLine> lines;
  for (char c : bytes) {
    if (auto line = framer.Push(static_cast<uint8_t>(c))) lines.push_back(*line);
  }
  return lines;
}

TEST(AtlLineFramer, CrLfOrCrLfEndOneLineAndEmptyLinesVanish) {
  const auto lines = Frame("JOG 10\rSTO\nPPO\r\n\r\n\rACL?\r\nJOG");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].text, "JOG 10");
  EXPECT_EQ(lines[1].text, "STO");
  EXPECT_EQ(lines[2].text, "PPO");
  EXPECT_EQ(lines[3].text, "ACL?");
  for (const AtlLine& l : lines) EXPECT_FALSE(l.overflowed);
}

TEST(AtlLineFramer, AnOverlongLineIsFlaggedAndTruncated) {
  const auto lines = Frame(std::string(20, 'A') + "\rSTO\r", 8);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_TRUE(lines[0].overflowed);
  EXPECT_EQ(lines[0].text, "AAAAAAAA");
  EXPECT_FALSE(lines[1].overflowed);
  EXPECT_EQ(ParseAtlLine(Table(), lines[0]).status, AtlParseStatus::kLineTooLong);
}

TEST(ParseAtlLine, ActionsQueriesAndArgumentSpellings) {
  AtlParsed p = Parse("JOG 100");
  EXPECT_EQ(p.status, AtlParseStatus::kOk);
  EXPECT_EQ(p.spec->operation, "rate");
  EXPECT_FALSE(p.query);
  EXPECT_EQ(p.argument, 100.0);
  p = Parse("  jog   -100 ");
  EXPECT_EQ(p.status, AtlParseStatus::kOk);
  EXPECT_EQ(p.argument, -100.0);
  EXPECT_EQ(Parse("JOG+25").argument, 25.0);
  p = Parse("P90");  // GM README: 'P' + number
  EXPECT_EQ(p.status, AtlParseStatus::kOk);
  EXPECT_EQ(p.spec->operation, "move");
  EXPECT_EQ(p.argument, 90.0);
  EXPECT_EQ(Parse("P -45.25").argument, -45.25);
  p = Parse("ACL?");
  EXPECT_EQ(p.status, AtlParseStatus::kOk);
  EXPECT_TRUE(p.query);
  EXPECT_EQ(Parse("PPO").status, AtlParseStatus::kOk);
  EXPECT_EQ(Parse("STO").status, AtlParseStatus::kOk);
  EXPECT_EQ(Parse("ACL 12.5").argument, 12.5);
}

TEST(ParseAtlLine, RefusalsAreTyped) {
  EXPECT_EQ(Parse("XYZ").status, AtlParseStatus::kUnknownCommand);
  EXPECT_EQ(Parse("123").status, AtlParseStatus::kUnknownCommand);
  EXPECT_EQ(Parse("RAT").status, AtlParseStatus::kUnknownCommand);   // query-only
  EXPECT_EQ(Parse("STO?").status, AtlParseStatus::kUnknownCommand);  // no query form
  EXPECT_EQ(Parse("JOG").status, AtlParseStatus::kBadArgument);
  EXPECT_EQ(Parse("JOG 12.5").status, AtlParseStatus::kBadArgument);  // integer argument (DRV)
  EXPECT_EQ(Parse("JOG ten").status, AtlParseStatus::kBadArgument);
  EXPECT_EQ(Parse("JOG 1 2").status, AtlParseStatus::kBadArgument);
  EXPECT_EQ(Parse("JOG ++1").status, AtlParseStatus::kBadArgument);
  EXPECT_EQ(Parse("STO 5").status, AtlParseStatus::kBadArgument);
  EXPECT_EQ(Parse("ACL? 5").status, AtlParseStatus::kBadArgument);
  EXPECT_EQ(Parse("ACL 1e3").status, AtlParseStatus::kBadArgument);  // fixed notation only
  const AtlParsed p = Parse("JOG 500");
  EXPECT_EQ(p.status, AtlParseStatus::kOutOfRange);
  EXPECT_EQ(p.argument, 500.0);
  EXPECT_EQ(Parse("JOG -361").status, AtlParseStatus::kOutOfRange);
  EXPECT_EQ(Parse("JOG 360").status, AtlParseStatus::kOk);  // limits are inclusive
  EXPECT_EQ(Parse("SRV 2").status, AtlParseStatus::kOutOfRange);
}

TEST(AtlReplies, FramingValuesAndErrorTemplates) {
  EXPECT_EQ(FrameAtlReply(Table().framing(), ""), "\r\n>\r\n");
  EXPECT_EQ(FrameAtlReply(Table().framing(), "12.500"), "12.500\r\n>\r\n");
  const AtlForm& jog_query = *Table().Find("JOG")->query;
  EXPECT_EQ(FormatAtlValue(jog_query, 12.5), "12.500");
  EXPECT_EQ(FormatAtlValue(jog_query, -0.0001), "0.000");  // never "-0.000"
  EXPECT_EQ(FormatAtlValue(jog_query, -99.9996), "-100.000");
  EXPECT_EQ(FormatAtlValue(*Table().Find("STA")->query, 5.0), "5");
  const AtlParsed p = Parse("JOG 500");
  EXPECT_EQ(FormatAtlError(Table().errors().out_of_range, p, "JOG 500"),
            "?OUT OF RANGE JOG 500 LIMITS -360 360 deg/s");
  EXPECT_EQ(
      FormatAtlError(Table().errors().out_of_range, p, "JOG 500", std::make_pair(-200.0, 200.0)),
      "?OUT OF RANGE JOG 500 LIMITS -200 200 deg/s");
  EXPECT_EQ(FormatAtlError("{line}|{mnemonic}|{min}", Parse("STO"), "STO"), "STO|STO|");
  EXPECT_EQ(AtlErrorTemplateFor(Table(), AtlParseStatus::kBadArgument),
            Table().errors().bad_argument);
}

TEST(EncodeAtlCommand, FormatsWhatTheParserAcceptsAndRefusesWhatItWouldRefuse) {
  EXPECT_EQ(EncodeAtlCommand(Table(), "JOG", 100.0), "JOG 100\r\n");
  EXPECT_EQ(EncodeAtlCommand(Table(), "JOG", -150.0), "JOG -150\r\n");
  EXPECT_EQ(EncodeAtlCommand(Table(), "JOG", std::nullopt, true), "JOG?\r\n");
  EXPECT_EQ(EncodeAtlCommand(Table(), "P", 12.25), "P 12.25\r\n");
  EXPECT_EQ(EncodeAtlCommand(Table(), "STO"), "STO\r\n");
  // Round trip through the server side.
  for (double rate : {-360.0, -1.0, 0.0, 7.0, 360.0}) {
    const auto lines = Frame(EncodeAtlCommand(Table(), "JOG", rate));
    ASSERT_EQ(lines.size(), 1u);
    const AtlParsed p = ParseAtlLine(Table(), lines[0]);
    EXPECT_EQ(p.status, AtlParseStatus::kOk);
    EXPECT_EQ(p.argument, rate);
  }
  try {
    EncodeAtlCommand(Table(), "JOG", 500.0);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("JOG 500 is outside [-360, 360] deg/s"));
  }
  EXPECT_THROW(EncodeAtlCommand(Table(), "JOG", 12.5), std::invalid_argument);
  EXPECT_THROW(EncodeAtlCommand(Table(), "JOG"), std::invalid_argument);
  EXPECT_THROW(EncodeAtlCommand(Table(), "STO", 1.0), std::invalid_argument);
  EXPECT_THROW(EncodeAtlCommand(Table(), "RAT"), std::invalid_argument);
  EXPECT_THROW(EncodeAtlCommand(Table(), "QQQ"), std::invalid_argument);
}

TEST(AtlReplyReader, CutsRepliesAcrossChunks) {
  AtlReplyReader reader(Table().framing());
  const std::string a = "\r\n>\r\n12.5";
  EXPECT_EQ(reader.Push({reinterpret_cast<const uint8_t*>(a.data()), a.size()}),
            std::vector<std::string>{""});
  EXPECT_EQ(reader.pending(), "12.5");
  const std::string b = "00\r\n>";
  EXPECT_TRUE(reader.Push({reinterpret_cast<const uint8_t*>(b.data()), b.size()}).empty());
  const std::string c = "\r\n?OUT\r\n>\r\n";
  EXPECT_EQ(reader.Push({reinterpret_cast<const uint8_t*>(c.data()), c.size()}),
            (std::vector<std::string>{"12.500", "?OUT"}));
  EXPECT_EQ(reader.pending(), "");
}

}  // namespace
}  // namespace adahrs::hil
