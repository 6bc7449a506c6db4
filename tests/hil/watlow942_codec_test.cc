#include "hil/codecs/watlow942_codec.h"

#include <set>

#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::hil {
namespace {

TEST(Watlow942Codec, DecodesTheManualsExamples) {
  // p. 10: `= A1LO 500` is 3D 20 41 31 4C 4F 20 35 30 30.
  const std::string bytes{0x3D, 0x20, 0x41, 0x31, 0x4C, 0x4F, 0x20, 0x35, 0x30, 0x30};
  const Watlow942Decoded write = DecodeWatlow942Line(bytes);
  ASSERT_TRUE(write.message) << write.reason;
  EXPECT_EQ(write.message->command, Watlow942Command::kWrite);
  EXPECT_EQ(write.message->mnemonic, "A1LO");
  EXPECT_EQ(write.message->data, std::vector<double>{500.0});
  // Lower case is accepted (p. 10); sign and decimal point in data.
  const Watlow942Decoded read = DecodeWatlow942Line("? stp 16");
  ASSERT_TRUE(read.message);
  EXPECT_EQ(read.message->command, Watlow942Command::kRead);
  EXPECT_EQ(read.message->mnemonic, "STP");
  EXPECT_EQ(read.message->data, std::vector<double>{16.0});
  const Watlow942Decoded negative = DecodeWatlow942Line("= SP1 -40.5");
  ASSERT_TRUE(negative.message);
  EXPECT_EQ(negative.message->data, std::vector<double>{-40.5});
}

TEST(Watlow942Codec, EncodesTheReadReplyOfTheManual) {
  // p. 13: the reply to `? A1LO` is 13 11 35 30 30 0D.
  EXPECT_EQ(EncodeWatlow942ReadReply({"500"}),
            std::string("\x13\x11"
                        "500\r"));
  EXPECT_EQ(EncodeWatlow942Request(Watlow942Command::kRead, "A1LO"), "? A1LO\r");
  EXPECT_EQ(EncodeWatlow942Request(Watlow942Command::kWrite, "A1LO", {"500"}), "= A1LO 500\r");
  EXPECT_EQ(DecodeWatlow942ReadReply("\x13\x11"
                                     "8 1 235 1 20 15 1 0\r"),
            "8 1 235 1 20 15 1 0");
  EXPECT_FALSE(
      DecodeWatlow942ReadReply("\x13\x11"
                               "50"));
}

TEST(Watlow942Codec, RefusesBadLinesWithTheEr2CodeAndOffset) {
  struct Case {
    std::string line;
    Watlow942Error error;
    size_t offset;
  };
  const std::vector<Case> cases = {
      {"", Watlow942Error::kIncompleteCommandLine, 0},
      {"X C1", Watlow942Error::kCommandNotFound, 0},
      {"??", Watlow942Error::kCommandNotFound, 0},
      {"?", Watlow942Error::kIncompleteCommandLine, 1},
      {"= SP1", Watlow942Error::kIncompleteCommandLine, 5},
      {"? ABCDE", Watlow942Error::kTooManyCharacters, 6},
      {"? C-1", Watlow942Error::kInvalidCharacter, 3},
      {"= SP1 12345678", Watlow942Error::kTooManyCharacters, 13},
      {"= SP1 1.2.3", Watlow942Error::kInvalidCharacter, 9},
      {"= SP1 -", Watlow942Error::kInvalidCharacter, 6},
      {"? C\x01", Watlow942Error::kInvalidCharacter, 3},
  };
  for (const Case& c : cases) {
    const Watlow942Decoded d = DecodeWatlow942Line(c.line);
    EXPECT_FALSE(d.message) << c.line;
    EXPECT_EQ(d.error, c.error) << c.line << ": " << d.reason;
    EXPECT_EQ(d.offset, c.offset) << c.line;
  }
}

TEST(Watlow942Codec, FormatsNumbersInSevenCharacters) {
  EXPECT_EQ(FormatWatlow942Number(25.04, 1), "25.0");
  EXPECT_EQ(FormatWatlow942Number(-0.04, 1), "0.0");
  EXPECT_EQ(FormatWatlow942Number(-40.0, 0), "-40");
  EXPECT_FALSE(FormatWatlow942Number(-9999.99, 2));  // 8 characters
  EXPECT_EQ(FormatWatlow942Number(-999.99, 2), "-999.99");
  EXPECT_FALSE(FormatWatlow942Number(12345678.0, 0));
}

TEST(Watlow942Codec, SplitterSeparatesFlowControlAndBoundsLines) {
  Watlow942LineSplitter splitter(8);
  std::vector<std::string> lines;
  std::vector<bool> overflowed;
  for (const char c : std::string("? C1\r\n\x13= SP1 4\x11"
                                  "0\r0123456789AB\r")) {
    if (auto line = splitter.Feed(static_cast<uint8_t>(c))) {
      lines.push_back(line->text);
      overflowed.push_back(line->overflowed);
    }
    if (c == '\x13') {
      EXPECT_TRUE(splitter.flow_paused());
    }
  }
  EXPECT_FALSE(splitter.flow_paused());
  EXPECT_EQ(lines, (std::vector<std::string>{"? C1", "= SP1 40", "01234567"}));
  EXPECT_EQ(overflowed, (std::vector<bool>{false, false, true}));
}

TEST(Watlow942Codec, SurvivesRandomGarbage) {
  // 20 000 random lines of random bytes and of near-miss text: every one decodes to a message or
  // to one of the documented ER2 codes with an offset inside the line.
  const std::set<Watlow942Error> known = {Watlow942Error::kCommandNotFound,
                                          Watlow942Error::kIncompleteCommandLine,
                                          Watlow942Error::kInvalidCharacter,
                                          Watlow942Error::kTooManyCharacters};
  common::Rng rng(942);
  const std::string alphabet = "?= 0123456789.-+ABCDSPTMRL\t";
  int messages = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string line;
    const int length = static_cast<int>(rng.Uniform(0.0, 20.0));
    for (int k = 0; k < length; ++k) {
      line.push_back(i % 2 ? static_cast<char>(rng.NextU64() & 0xFF)
                           : alphabet[rng.NextU64() % alphabet.size()]);
    }
    const Watlow942Decoded d = DecodeWatlow942Line(line);
    if (d.message) {
      ++messages;
      EXPECT_LE(d.message->mnemonic.size(), kWatlow942MaxMnemonicChars);
    } else {
      EXPECT_TRUE(known.count(d.error)) << static_cast<int>(d.error);
      EXPECT_LE(d.offset, line.size());
    }
  }
  EXPECT_GT(messages, 0);  // the near-miss half does produce valid messages
}

}  // namespace
}  // namespace adahrs::hil
