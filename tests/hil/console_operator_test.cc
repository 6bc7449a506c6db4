#include "hil/drivers/console_operator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "hil/instruments/instrument_error.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

TEST(ConsoleOperator, PrintsWhatToDoAndWaitsForEnter) {
  std::istringstream in("\n\n");
  std::ostringstream out;
  ConsoleOperator op(in, out);
  op.Mount({"imu1", "imu2"}, 22);
  EXPECT_THAT(out.str(), HasSubstr("Mount imu1, imu2 in fixture orientation 22 (-Y up)"));
  op.Prompt("Open the chamber door");
  EXPECT_THAT(out.str(), HasSubstr("Open the chamber door"));
  // Two confirmations consumed, none left: the next question meets end of input = abort.
  try {
    op.Mount({"imu1"}, 31);
    FAIL() << "end of input was taken as a confirmation";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.role(), "operator");
    EXPECT_THAT(e.what(), HasSubstr("aborted"));
  }
}

}  // namespace
}  // namespace adahrs::hil
