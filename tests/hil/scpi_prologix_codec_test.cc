#include <gtest/gtest.h>

#include "common/random.h"
#include "hil/codecs/prologix.h"
#include "hil/codecs/scpi.h"

namespace adahrs::hil {
namespace {

TEST(ScpiCodec, ParsesHeadersQueriesAndArguments) {
  const ScpiParsed p = ParseScpiCommand(":sour:pres PS, 1013.25");
  ASSERT_TRUE(p.command) << p.reason;
  EXPECT_EQ(p.command->headers, (std::vector<std::string>{"SOUR", "PRES"}));
  EXPECT_FALSE(p.command->query);
  EXPECT_EQ(p.command->args, (std::vector<std::string>{"PS", "1013.25"}));
  EXPECT_TRUE(ScpiHeadersMatch(*p.command, {"SOURce", "PRESsure"}));
  const ScpiParsed idn = ParseScpiCommand("*IDN?");
  ASSERT_TRUE(idn.command);
  EXPECT_TRUE(idn.command->common && idn.command->query);
  EXPECT_TRUE(ScpiHeaderMatches("STATus", "status"));
  EXPECT_FALSE(ScpiHeaderMatches("STATus", "STATU"));
  EXPECT_EQ(SplitScpiProgram("SOUR:STAT ON;MEAS:PRES? PS\r\n"),
            (std::vector<std::string>{"SOUR:STAT ON", "MEAS:PRES? PS"}));
  EXPECT_EQ(ParseScpiNumber("-1.5E+2"), -150.0);
  EXPECT_FALSE(ParseScpiNumber("1.5X"));
  EXPECT_FALSE(ParseScpiNumber("."));
  EXPECT_EQ(FormatScpiNumber(1013.25, 8), "1013.25");
}

TEST(ScpiCodec, RefusesMalformedCommandsWithSyntaxErrors) {
  for (const char* text :
       {"", "1ABC", "SOUR:", "SOUR:PRES PS,,1", "MEAS:PRES?PS", "A\x01", "X \"open"}) {
    const ScpiParsed p = ParseScpiCommand(text);
    EXPECT_FALSE(p.command) << text;
    EXPECT_EQ(p.error, kScpiSyntaxError) << text;
  }
}

TEST(PrologixCodec, SplitsLinesAndHonoursEscapes) {
  PrologixLineSplitter splitter;
  std::vector<PrologixLine> lines;
  // A command, a data line with an escaped LF inside, and data starting with escaped "++".
  const std::string bytes = "++addr 5\r\n*IDN?\x1b\nX\n\x1b+\x1b+ver\n";
  for (const char c : bytes) {
    if (auto line = splitter.Feed(static_cast<uint8_t>(c))) lines.push_back(*line);
  }
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_TRUE(lines[0].is_command);
  EXPECT_EQ(lines[0].text, "addr 5");
  EXPECT_FALSE(lines[1].is_command);
  EXPECT_EQ(lines[1].text, "*IDN?\nX");
  EXPECT_FALSE(lines[2].is_command);
  EXPECT_EQ(lines[2].text, "++ver");
  EXPECT_EQ(EscapePrologixData("a+\r"), "a\x1b+\x1b\r");
}

TEST(PrologixCodec, CommandsSetAndQuerySettings) {
  PrologixController c("Prologix GPIB-USB Controller version 6.107");
  // Power-up defaults of the manual (§8): auto 0, eoi 1, eos 0, read_tmo_ms 500.
  EXPECT_EQ(c.Apply("auto").reply, "0\r\n");
  EXPECT_EQ(c.Apply("eoi").reply, "1\r\n");
  EXPECT_EQ(c.Apply("eos").reply, "0\r\n");
  EXPECT_EQ(c.Apply("read_tmo_ms").reply, "500\r\n");
  c.Apply("addr 9 96");
  EXPECT_EQ(c.Apply("addr").reply, "9 96\r\n");
  c.Apply("eos 3");
  EXPECT_EQ(c.settings().eos, 3);
  EXPECT_EQ(c.Apply("ver").reply, "Prologix GPIB-USB Controller version 6.107\r\n");
  EXPECT_EQ(c.Apply("addr 31").kind, PrologixAction::Kind::kIgnored);
  EXPECT_EQ(c.settings().address, 9);
  EXPECT_EQ(c.Apply("read_tmo_ms 3001").kind, PrologixAction::Kind::kIgnored);
  EXPECT_EQ(c.Apply("frobnicate").kind, PrologixAction::Kind::kIgnored);
  const PrologixAction read = c.Apply("read eoi");
  EXPECT_EQ(read.kind, PrologixAction::Kind::kRead);
  EXPECT_TRUE(read.read_until_eoi);
  EXPECT_EQ(c.Apply("read 10").read_until_char, 10);
  EXPECT_EQ(PrologixEosTerminator(0), "\r\n");
  EXPECT_EQ(PrologixEosTerminator(3), "");
}

TEST(ScpiPrologixCodec, SurviveRandomGarbage) {
  common::Rng rng(488);
  PrologixLineSplitter splitter(64);
  PrologixController controller("v");
  const std::string alphabet = "+*:;?, .0123456789ABCDEFGHIMNOPRSTUVaeiorstd\"\x1b\r\n";
  int commands = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string text;
    const int length = static_cast<int>(rng.Uniform(0.0, 24.0));
    for (int k = 0; k < length; ++k) {
      text.push_back(i % 2 ? static_cast<char>(rng.NextU64() & 0xFF)
                           : alphabet[rng.NextU64() % alphabet.size()]);
    }
    for (const std::string& command : SplitScpiProgram(text)) {
      const ScpiParsed p = ParseScpiCommand(command);
      if (p.command) {
        ++commands;
      } else {
        EXPECT_LE(p.offset, command.size());
      }
    }
    for (const char c : text) {
      if (auto line = splitter.Feed(static_cast<uint8_t>(c))) {
        EXPECT_LE(line->text.size(), 64u);
        if (line->is_command) controller.Apply(line->text);
      }
    }
    ParseScpiNumber(text);
  }
  EXPECT_GT(commands, 0);
  EXPECT_LE(controller.settings().address, 30);
  EXPECT_GE(controller.settings().read_tmo_ms, 1);
}

}  // namespace
}  // namespace adahrs::hil
