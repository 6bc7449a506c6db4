// InstrumentError quotes what an instrument sent with its control bytes escaped, so a reply of
// binary noise or a stray CR cannot rewrite the operator's terminal line.
#include "hil/instruments/instrument_error.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

TEST(InstrumentError, QuotesTheReplyWithControlBytesEscaped) {
  const InstrumentError error(InstrumentError::Kind::kBadReply,
                              "rate_table",
                              "/dev/ttyS0",
                              "RAT?",
                              "12.5\r\n>\x1b[2K\xff",
                              "expected a number");
  const std::string text = error.what();
  EXPECT_THAT(text, HasSubstr("rate_table on /dev/ttyS0: RAT?: unexpected reply"));
  EXPECT_THAT(text, HasSubstr("reply '12.5\\r\\n>\\x1B[2K\\xFF'"));
  EXPECT_EQ(text.find_first_of("\r\n\x1b\xff"), std::string::npos) << text;
  EXPECT_EQ(error.reply(), "12.5\\r\\n>\\x1B[2K\\xFF");
}

TEST(InstrumentError, PrintableReplyIsQuotedAsIs) {
  const InstrumentError error(InstrumentError::Kind::kRefused,
                              "adts",
                              "/dev/ttyUSB1",
                              "SOUR:PRES",
                              "-222,\"Data out of range\"",
                              "");
  EXPECT_THAT(std::string(error.what()), HasSubstr("reply '-222,\"Data out of range\"'"));
}

}  // namespace
}  // namespace adahrs::hil
