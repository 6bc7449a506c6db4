// PrintableText / PrintableMessage: what a message may quote of untrusted bytes, against escapes
// written out by hand.
#include "common/printable_text.h"

#include <gtest/gtest.h>

#include <string>

namespace adahrs::common {
namespace {

TEST(PrintableText, KeepsPrintableAsciiAndUtf8) {
  EXPECT_EQ(PrintableText("JOG -100 'ok'"), "JOG -100 'ok'");
  EXPECT_EQ(PrintableText("25 \xC2\xB0"
                          "C \xE2\x80\xA6"),
            "25 \xC2\xB0"
            "C \xE2\x80\xA6");  // ° …
  EXPECT_EQ(PrintableText(""), "");
}

TEST(PrintableText, EscapesLineEndsTabsAndBackslash) {
  EXPECT_EQ(PrintableText("12.5\r\n>\r\n"), "12.5\\r\\n>\\r\\n");
  EXPECT_EQ(PrintableText("a\tb\\c"), "a\\tb\\\\c");
}

TEST(PrintableText, EscapesControlBytesAsHex) {
  EXPECT_EQ(PrintableText("\x1b[2J"), "\\x1B[2J");
  EXPECT_EQ(PrintableText(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(PrintableText("\x11\x13\x7f"), "\\x11\\x13\\x7F");
}

TEST(PrintableText, EscapesBytesThatAreNotUtf8OrAreC1Controls) {
  EXPECT_EQ(PrintableText("\xff\xfe"), "\\xFF\\xFE");
  EXPECT_EQ(PrintableText("\xC2\x9B"
                          "31m"),
            "\\xC2\\x9B31m");                                   // U+009B, the 8-bit CSI
  EXPECT_EQ(PrintableText("\xC0\xAF"), "\\xC0\\xAF");           // overlong '/'
  EXPECT_EQ(PrintableText("\xE2\x80"), "\\xE2\\x80");           // cut short
  EXPECT_EQ(PrintableText("\xED\xA0\x80"), "\\xED\\xA0\\x80");  // a surrogate
}

TEST(PrintableMessage, KeepsLineBreaksAndBackslashesEscapesTheRest) {
  EXPECT_EQ(PrintableMessage("2 problems:\n  a\r\n  b \\r \x1b[31m"),
            "2 problems:\n  a\\r\n  b \\r \\x1B[31m");
}

}  // namespace
}  // namespace adahrs::common
